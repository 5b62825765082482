// Minimal checking helpers shared by the test programs: every check prints
// what it compared and the test's exit code says whether all of them held.
#ifndef sable_tests_test_support_h
#define sable_tests_test_support_h

#include <cmath>
#include <iostream>
#include <string>

namespace sable_tests
{
  inline int &
  n_failures()
  {
    static int n = 0;
    return n;
  }

  /// Check |value - expected| <= tolerance * max(|expected|, floor).
  inline bool
  check_relative(const std::string &what,
                 const double       value,
                 const double       expected,
                 const double       tolerance,
                 const double       floor = 0.)
  {
    const double scale = std::max(std::abs(expected), floor);
    const double error = std::abs(value - expected);
    const bool   ok = std::isfinite(value) && error <= tolerance * scale;
    std::cout << (ok ? "[ ok ] " : "[FAIL] ") << what << ": value " << value
              << ", expected " << expected << ", relative error "
              << (scale > 0 ? error / scale : error) << " (tolerance "
              << tolerance << ")" << std::endl;
    if (!ok)
      ++n_failures();
    return ok;
  }

  inline bool
  check(const std::string &what, const bool condition)
  {
    std::cout << (condition ? "[ ok ] " : "[FAIL] ") << what << std::endl;
    if (!condition)
      ++n_failures();
    return condition;
  }

  inline int
  exit_code()
  {
    std::cout << (n_failures() == 0 ? "all checks passed" :
                                      std::to_string(n_failures()) +
                                        " check(s) failed")
              << std::endl;
    return n_failures() == 0 ? 0 : 1;
  }
} // namespace sable_tests

#endif
