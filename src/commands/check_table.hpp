#pragma once
// `sympl check-table`: a user's table validated, its order measured and read
// exactly off its BCH series, its stability interval and error at equal cost.
#include <string>

namespace sympl::app {

// Prints the result (text or JSON); returns the exit code.
int check_table(const std::string& kick_text, const std::string& drift_text, const std::string& convention, bool json);

}  // namespace sympl::app
