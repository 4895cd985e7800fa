#include "jobs/farm_merge.h"

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "io/atomic_file.h"
#include "util/version.h"

namespace fs = std::filesystem;

namespace seasim {

namespace {

// The item's own report.json (verified by its checksum when the item is done), or null.
nlohmann::json itemReport(const std::string& output_dir, const std::string& name) {
  try {
    std::ifstream in(output_dir + "/" + name + "/report.json");
    if (!in) return nullptr;
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    return nullptr;
  }
}

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

std::string whyMissing(const ItemState& s) {
  switch (s.status) {
    case ItemState::Status::Failed:
      return "failed: " + s.detail.substr(0, s.detail.find('\n'));
    case ItemState::Status::Damaged:
      return "damaged: " + s.detail;
    case ItemState::Status::Missing:
      return "not rendered";
    case ItemState::Status::Done:
      return "done";
  }
  return "";
}

std::string contactSheet(const Job& job, const nlohmann::json& items, bool complete) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" << htmlEscape(job.name)
    << " — contact sheet</title>\n<style>body{font-family:sans-serif;background:#222;color:#ddd}"
       "figure{display:inline-block;margin:6px;vertical-align:top;width:240px}img{width:240px}"
       "figcaption{font-size:12px}.bad{color:#f66}</style></head><body>\n<h1>"
    << htmlEscape(job.name) << "</h1>\n<p>" << items.size() << " items"
    << (complete ? ", all done" : ", <span class=\"bad\">incomplete</span>") << ". Written by seasim farm merge.</p>\n";
  for (const auto& item : items) {
    const std::string name = item["name"].get<std::string>();
    h << "<figure>";
    const bool has_png = item.contains("files") && item["files"].contains(name + "/image.png");
    if (item["status"] == "done" && has_png)
      h << "<a href=\"../" << htmlEscape(name) << "/image.png\"><img src=\"../" << htmlEscape(name)
        << "/image.png\" alt=\"" << htmlEscape(name) << "\"></a>";
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

}  // namespace

MergeResult mergeFarmJob(const Job& job) {
  MergeResult result;
  const std::vector<ItemState> states = readItemStates(job, job.output_dir, true);
  result.total = static_cast<int>(states.size());
  nlohmann::json items = nlohmann::json::array();
  std::set<std::string> devices;
  double wall_total = 0;
  for (const ItemState& s : states) {
    nlohmann::json item = {{"name", s.name}, {"status", statusName(s.status)}};
    if (s.status == ItemState::Status::Done) {
      item["files"] = s.files;
      item["wall_ms"] = s.wall_ms;
      item["kernel_ms"] = s.kernel_ms;
      wall_total += s.wall_ms;
      const nlohmann::json report = itemReport(job.output_dir, s.name);
      if (!report.is_null()) {
        for (const char* key : {"pass_ms", "kernel_build_ms", "device", "nonfinite", "error"})
          if (report.contains(key)) item[key] = report[key];
        if (report.contains("device") && report["device"].contains("label"))
          devices.insert(report["device"]["label"].get<std::string>());
      }
    } else {
      result.missing.push_back(s);
      item["error"] = whyMissing(s);
      if (s.status == ItemState::Status::Failed) item["error"] = s.detail;
    }
    items.push_back(item);
  }
  const bool complete = result.missing.empty();
  nlohmann::json missing = nlohmann::json::array();
  for (const ItemState& s : result.missing) missing.push_back(s.name);
  const nlohmann::json summary = {{"seasim", {{"version", version()}, {"git_commit", gitCommit()}}},
                                  {"job", job.name},
                                  {"job_file", job.file},
                                  {"output_dir", job.output_dir},
                                  {"complete", complete},
                                  {"items_total", result.total},
                                  {"items_done", result.total - static_cast<int>(result.missing.size())},
                                  {"missing", missing},
                                  {"wall_ms_total", wall_total},
                                  {"devices", devices},
                                  {"items", items}};
  result.report = job.output_dir + "/farm/report.json";
  result.contact_sheet = job.output_dir + "/farm/contact_sheet.html";
  writeTextAtomic(result.contact_sheet, contactSheet(job, items, complete));
  writeTextAtomic(result.report, summary.dump(2) + "\n");  // last: its "complete" covers the sheet too
  return result;
}

std::string missingItemsMessage(const MergeResult& r) {
  std::string msg = std::to_string(r.missing.size()) + " of " + std::to_string(r.total) + " items are missing:";
  for (const ItemState& s : r.missing) msg += "\n  " + s.name + " (" + whyMissing(s) + ")";
  return msg;
}

}  // namespace seasim
