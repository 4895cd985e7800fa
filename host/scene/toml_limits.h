// toml_limits.h — how deep a scene, job or override may nest, checked on the text before toml++
// parses it. toml++ descends recursively into dotted keys, table headers and nested arrays/inline
// tables: a key of 40,000 parts overflowed the 8 MiB stack (SIGSEGV inside the parser), 5,000 a
// 1 MiB one. No seasim file needs more than a few levels, so the limits are far below any stack.
#pragma once
#include <string>
#include <string_view>

namespace seasim {

constexpr int kMaxTomlKeyParts = 64;  // parts of one dotted key or table header ("a.b.c" has 3)
constexpr int kMaxTomlNesting = 64;   // arrays and inline tables inside each other

// Throws InputError(file, line of the offending key or bracket, "", why) when `text` has a dotted
// key or header of more than kMaxTomlKeyParts parts or brackets nested deeper than kMaxTomlNesting.
// Strings and comments are skipped (a quoted key's dots are not parts). `first_line` is the line
// number of the text's first line in `file`.
void checkTomlLimits(std::string_view text, const std::string& file, int first_line = 1);

}  // namespace seasim
