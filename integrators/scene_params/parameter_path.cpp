#include "integrators/scene_params/parameter_path.h"

#include <cctype>

#include "core/error.h"

namespace nx {

std::vector<ParameterStep> parameterSteps(const std::string& name) {
  std::vector<ParameterStep> out;
  auto bad = [&] { return Error("no scene parameter named '" + name + "'"); };
  size_t i = 0;
  while (i < name.size()) {
    ParameterStep s;
    while (i < name.size() && (std::isalnum(static_cast<unsigned char>(name[i])) || name[i] == '_'))
      s.attribute += name[i++];
    if (s.attribute.empty()) throw bad();
    if (i < name.size() && name[i] == '[') {
      const size_t close = name.find(']', i);
      if (close == std::string::npos) throw bad();
      const std::string inside = name.substr(i + 1, close - i - 1);
      if (inside.size() >= 2 && (inside.front() == '\'' || inside.front() == '"') &&
          inside.back() == inside.front())
        s.index = inside.substr(1, inside.size() - 2);
      else if (!inside.empty() && inside.size() <= 18 &&
               inside.find_first_not_of("0123456789") == std::string::npos)
        s.index = static_cast<size_t>(std::stoull(inside));
      else
        throw bad();
      i = close + 1;
    }
    out.push_back(std::move(s));
    if (i < name.size()) {
      if (name[i] != '.') throw bad();
      ++i;
      if (i == name.size()) throw bad();
    }
  }
  if (out.empty() || out.back().index.index() != 0) throw bad();
  return out;
}

std::string canonicalParameterName(std::string name) {
  for (char& ch : name)
    if (ch == '"') ch = '\'';
  return name;
}

} // namespace nx
