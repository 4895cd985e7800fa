#include "scene/toml_limits.h"

#include "util/error.h"

namespace seasim {

namespace {

// The scanner's state between characters: outside strings, or inside one of TOML's four string
// kinds, or in a comment. Only the structure matters here; toml++ reports every syntax error.
enum class Lex { Plain, Basic, Literal, MultiBasic, MultiLiteral, Comment };

bool startsWith(std::string_view text, size_t i, std::string_view what) { return text.substr(i, what.size()) == what; }

}  // namespace

void checkTomlLimits(std::string_view text, const std::string& file, int first_line) {
  Lex lex = Lex::Plain;
  int line = first_line;
  int depth = 0;  // open [ and { outside strings (a [[header]] counts 2 while open)
  int dots = 0;   // '.' since the last key/value boundary: parts - 1 of a dotted key (a float has 1)
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') ++line;
    switch (lex) {
      case Lex::Comment:
        if (c == '\n') lex = Lex::Plain, dots = 0;
        continue;
      case Lex::Basic:
        if (c == '\\') ++i;  // an escaped quote or backslash (a newline here is a syntax error anyway)
        else if (c == '"' || c == '\n') lex = Lex::Plain;
        continue;
      case Lex::Literal:
        if (c == '\'' || c == '\n') lex = Lex::Plain;
        continue;
      case Lex::MultiBasic:
        if (c == '\\' && i + 1 < text.size() && text[i + 1] != '\n') ++i;
        else if (startsWith(text, i, "\"\"\"")) lex = Lex::Plain, i += 2;
        continue;
      case Lex::MultiLiteral:
        if (startsWith(text, i, "'''")) lex = Lex::Plain, i += 2;
        continue;
      case Lex::Plain:
        break;
    }
    switch (c) {
      case '#':
        lex = Lex::Comment;
        break;
      case '"':
        if (startsWith(text, i, "\"\"\"")) lex = Lex::MultiBasic, i += 2;
        else lex = Lex::Basic;
        break;
      case '\'':
        if (startsWith(text, i, "'''")) lex = Lex::MultiLiteral, i += 2;
        else lex = Lex::Literal;
        break;
      case '.':
        if (++dots >= kMaxTomlKeyParts)
          throw InputError(file, line, "",
                           "a dotted key or table header with more than " + std::to_string(kMaxTomlKeyParts) +
                               " parts; seasim's keys have a few (refused before parsing: so many parts can "
                               "overflow the TOML parser's stack)");
        break;
      case '[':
      case '{':
        dots = 0;
        if (++depth > kMaxTomlNesting)
          throw InputError(file, line, "",
                           "arrays or inline tables nested more than " + std::to_string(kMaxTomlNesting) +
                               " deep (refused before parsing: deeper nesting can overflow the TOML parser's stack)");
        break;
      case ']':
      case '}':
        dots = 0;
        if (depth > 0) --depth;
        break;
      case '=':
      case ',':
      case '\n':
        dots = 0;
        break;
      default:
        break;
    }
  }
}

}  // namespace seasim
