// Build-time generator of the built-in sRGB sigmoid-coefficient table: fits every entry (the
// independent pieces in parallel) and writes the table's binary form.
//   nx_generate_sigmoid_table RESOLUTION OUTPUT

#include <tbb/parallel_for.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

#include "spectra/sigmoid_table.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: nx_generate_sigmoid_table RESOLUTION OUTPUT\n";
    return 2;
  }
  const int res = std::atoi(argv[1]);
  if (res < 3 || res > 256) {
    std::cerr << "nx_generate_sigmoid_table: expected a resolution in 3..256, found " << argv[1]
              << "\n";
    return 2;
  }
  const auto parallel = [](int count, const std::function<void(int)>& body) {
    tbb::parallel_for(0, count, [&](int i) { body(i); });
  };
  const nx::SigmoidTable table(res, nx::SigmoidTable::zPositions(res),
                               nx::SigmoidTable::fit(res, parallel));
  const std::string bytes = table.toBytes();
  const std::string tmp = std::string(argv[2]) + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) {
      std::cerr << "nx_generate_sigmoid_table: cannot write " << tmp << "\n";
      return 1;
    }
  }
  if (std::rename(tmp.c_str(), argv[2]) != 0) {
    std::cerr << "nx_generate_sigmoid_table: cannot rename " << tmp << " to " << argv[2] << "\n";
    return 1;
  }
  return 0;
}
