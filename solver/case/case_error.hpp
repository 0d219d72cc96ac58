// The user-facing input error of a case, apart from the Case itself: the stages that get specs
// (case/specs/) and check rules against their values throw it without including the Case.
#pragma once

#include <stdexcept>
#include <string>

namespace needlefem {

// One-line, user-facing input error: "FILE: key 'a.b': reason".
class CaseError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A CaseError "ORIGIN: key 'KEY': REASON": Case::error's message, for the rules checked where a
// spec's values are used (case/specs/), which know the case's origin but not the Case.
CaseError case_error(const std::string& origin, const std::string& key, const std::string& reason);

}  // namespace needlefem
