#pragma once
// Lookups every kind registry shares (material, light, shape and medium kinds): a kind by its
// name, the kinds' names for messages, a kind's parameter by its name.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace nx {

/// The kind of `kinds` called `name` (its `name` field), or null.
template <class Spec>
const Spec* findKindNamed(std::span<const Spec> kinds, std::string_view name) {
  for (const Spec& k : kinds)
    if (name == k.name) return &k;
  return nullptr;
}

/// "a, b or c": the kinds' names for messages.
template <class Spec>
std::string kindNameList(std::span<const Spec> kinds) {
  std::vector<std::string> names;
  for (const Spec& k : kinds) names.push_back(k.name);
  return listWithOr(names);
}

/// The parameter of `params` called `name` (its `spec.name`), or null.
template <class Param>
const Param* findParameterNamed(std::span<const Param> params, std::string_view name) {
  for (const Param& p : params)
    if (name == p.spec.name) return &p;
  return nullptr;
}

} // namespace nx
