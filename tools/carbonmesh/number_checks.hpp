#pragma once
// Checks of numeric option values that say what is wrong in words. CLI11's PositiveNumber and NonNegativeNumber name
// their range up to the largest double written out in full (309 digits); these give "-1 must be a positive number".
#include <CLI/CLI.hpp>

#include <cmath>
#include <string>

namespace carbonmesh::cli {

// A finite number, > 0 (`zero_allowed` false) or >= 0; `name` is the type shown in the help.
inline CLI::Validator number_check(bool zero_allowed, const std::string& name) {
  return CLI::Validator(
      [zero_allowed](std::string& input) -> std::string {
        double value = 0;
        if (!CLI::detail::lexical_cast(input, value)) return input + " is not a number";
        if (std::isfinite(value) && (zero_allowed ? value >= 0 : value > 0)) return {};
        return input + (zero_allowed ? " must be a finite number, not negative" : " must be a positive number");
      },
      name);
}

// For CLI11's PositiveNumber: > 0 and finite.
inline CLI::Validator positive_number() { return number_check(false, "POSITIVE"); }
// For CLI11's NonNegativeNumber: >= 0 and finite.
inline CLI::Validator non_negative_number() { return number_check(true, "NONNEGATIVE"); }

}  // namespace carbonmesh::cli
