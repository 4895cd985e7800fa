#include "scene/set_option.h"

#include <toml++/toml.h>

#include "scene/toml_limits.h"
#include "util/error.h"

namespace seasim {

Override parseSetOption(const std::string& text) {
  const size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw InputError("<command line>", 0, text, "--set expects key=value, e.g. --set sun.zenith_deg=40");
  }
  std::string key = text.substr(0, eq);
  std::string value = text.substr(eq + 1);
  checkTomlLimits(value, "<command line --set " + key.substr(0, 80) + "=...>", 0);
  try {
    (void)toml::parse("v = " + value);
  } catch (const toml::parse_error&) {
    std::string quoted = "\"";  // not TOML: take it as a string (--set water.jerlov=IB)
    for (char c : value) quoted += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
    value = quoted + "\"";
  }
  // A long --set (a key of thousands of parts) is named by its start.
  const std::string shown = text.size() > 80 ? text.substr(0, 80) + "..." : text;
  return Override{key, value, SourceLoc{"<command line --set " + shown + ">", 0}};
}

}  // namespace seasim
