// The enumerator a choice key's value names, for the spec parsers (case/specs/*.cpp), and the
// choice an enumerator stands for, for messages: `names` pairs each of the schema's choices with
// its enumerator.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

#include "case/case.hpp"

namespace needlefem {

template <class Names>
auto parse_choice(const Case& c, const std::string& key, const Names& names) {
  const std::string value = c.text(key);
  for (const auto& [name, enumerator] : names)
    if (name == value) return enumerator;
  // The schema refuses any value outside its choices: a choice missing here is a programming error.
  throw std::logic_error("case key '" + key + "': the choice '" + value + "' has no enumerator");
}

template <class Names, class Enumerator>
const auto& choice_name(const Names& names, Enumerator enumerator) {
  for (const auto& [name, named] : names)
    if (named == enumerator) return name;
  // Every enumerator of a choice key has a choice: one missing in `names` is a programming error.
  throw std::logic_error("an enumerator without a choice");
}

}  // namespace needlefem
