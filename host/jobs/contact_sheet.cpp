#include "jobs/contact_sheet.h"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "io/atomic_file.h"

namespace seasim {

namespace {

std::string htmlEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

nlohmann::json itemReport(const std::string& output_dir, const std::string& name) {
  try {
    std::ifstream in(output_dir + "/" + name + "/report.json");
    if (!in) return nullptr;
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    return nullptr;
  }
}

}  // namespace

std::string contactSheetHtml(const Job& job, const nlohmann::json& items, bool complete,
                             const std::string& image_prefix, const std::string& written_by) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" << htmlEscape(job.name)
    << " — contact sheet</title>\n<style>body{font-family:sans-serif;background:#222;color:#ddd}"
       "figure{display:inline-block;margin:6px;vertical-align:top;width:240px}img{width:240px}"
       "figcaption{font-size:12px}.bad{color:#f66}</style></head><body>\n<h1>"
    << htmlEscape(job.name) << "</h1>\n<p>" << items.size() << " items"
    << (complete ? ", all done" : ", <span class=\"bad\">incomplete</span>") << ". Written by "
    << htmlEscape(written_by) << ".</p>\n";
  for (const auto& item : items) {
    const std::string name = item["name"].get<std::string>();
    const std::string png = image_prefix + name + "/image.png";
    h << "<figure>";
    const bool has_png = item.contains("files") && item["files"].contains(name + "/image.png");
    if (item["status"] == "done" && has_png)
      h << "<a href=\"" << htmlEscape(png) << "\"><img src=\"" << htmlEscape(png) << "\" loading=\"lazy\" alt=\""
        << htmlEscape(name) << "\"></a>";
    h << "<figcaption>" << htmlEscape(name);
    if (item["status"] != "done") {
      h << " <span class=\"bad\">" << htmlEscape(item["status"].get<std::string>()) << "</span>";
    } else {
      char ms[64];
      std::snprintf(ms, sizeof ms, "%.0f ms", item.value("wall_ms", 0.0));
      h << "<br>" << ms;
      if (item.contains("device")) h << " · " << htmlEscape(item["device"].value("label", ""));
      if (!has_png) h << "<br>(no PNG output)";
    }
    h << "</figcaption></figure>\n";
  }
  h << "</body></html>\n";
  return h.str();
}

nlohmann::json itemsJson(const Job& job, const std::vector<ItemState>& states) {
  nlohmann::json items = nlohmann::json::array();
  for (const ItemState& s : states) {
    nlohmann::json item = {{"name", s.name}, {"status", statusName(s.status)}};
    if (s.status == ItemState::Status::Done) {
      item["files"] = s.files;
      item["wall_ms"] = s.wall_ms;
      item["kernel_ms"] = s.kernel_ms;
      const nlohmann::json report = itemReport(job.output_dir, s.name);
      if (!report.is_null())
        for (const char* key : {"pass_ms", "kernel_build_ms", "device", "nonfinite", "error"})
          if (report.contains(key)) item[key] = report[key];
    } else if (s.status == ItemState::Status::Failed) {
      item["error"] = s.detail;
    }
    items.push_back(item);
  }
  return items;
}

std::string writeRunContactSheet(const Job& job) {
  const nlohmann::json items = itemsJson(job, readItemStates(job, job.output_dir, true));
  bool complete = true;
  for (const auto& item : items) complete = complete && item["status"] == "done";
  const std::string path = job.output_dir + "/index.html";
  writeTextAtomic(path, contactSheetHtml(job, items, complete, "", "seasim run"));
  return path;
}

}  // namespace seasim
