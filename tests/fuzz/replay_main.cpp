// A main() for the fuzz targets without libFuzzer: feeds each file named on the command line
// to LLVMFuzzerTestOneInput, in one process, naming each before it runs. Built with the
// ordinary compiler, it replays a fuzz corpus under valgrind, which sees errors inside the
// system libraries the sanitizers do not instrument (the mesh library, OpenEXR, GDAL).
//
//   NX_FUZZ_KIND=ply valgrind input_fuzzer_replay corpus/*

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv);
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

int main(int argc, char** argv) {
  LLVMFuzzerInitialize(&argc, &argv);
  for (int i = 1; i < argc; ++i) {
    std::ifstream in(argv[i], std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    std::fprintf(stderr, "replay: %s (%zu bytes)\n", argv[i], bytes.size());
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  }
  return 0;
}
