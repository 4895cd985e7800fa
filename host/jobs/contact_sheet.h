// contact_sheet.h — one HTML page with every item's PNG, its name, render time and device, read
// from the files on disk (each item's manifest entry and report.json), so it shows what is really
// there. `seasim run` writes <output_dir>/index.html after an unsharded run; `seasim farm merge`
// writes <output_dir>/farm/contact_sheet.html after the shards.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "jobs/farm_items.h"
#include "jobs/job.h"

namespace seasim {

// `items`: one object per item in job order, {"name", "status" ("done", "failed", ...), and for done
// items "files" (relative path -> checksum), "wall_ms", optionally "device" {"label"}}.
// `image_prefix` is the path from the sheet's folder to the output folder ("" or "../").
std::string contactSheetHtml(const Job& job, const nlohmann::json& items, bool complete,
                             const std::string& image_prefix, const std::string& written_by);

// The items in the form above, from their states (readItemStates) and each done item's report.json.
nlohmann::json itemsJson(const Job& job, const std::vector<ItemState>& states);

// Writes <output_dir>/index.html atomically from the items found there (checksums verified);
// returns its path.
std::string writeRunContactSheet(const Job& job);

}  // namespace seasim
