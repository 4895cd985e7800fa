#include "passes/sea_heightfield.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "device/enqueue.h"
#include "device/kernel_store.h"
#include "io/atomic_file.h"
#include "io/data_files.h"
#include "io/image_io.h"
#include "util/error.h"
#include "util/hash.h"
#include "util/paths.h"

namespace seasim {

// The kernels read this struct with OpenCL C layout; float/int are 4 bytes on both sides.
static_assert(sizeof(SeaHeightField) == 32, "SeaHeightField layout changed: update sea_bottom_params.h users");
static_assert(offsetof(SeaHeightField, extent) == 8);
static_assert(offsetof(SeaHeightField, max_cells) == 20);

namespace fs = std::filesystem;

HeightField makeHeightField(int nx, int ny, double extent, std::vector<float> depth) {
  if (nx < 2 || ny < 2) throw RuntimeError("a height-field floor needs at least 2 x 2 nodes");
  if (depth.size() != static_cast<size_t>(nx) * ny) throw RuntimeError("height field: depth count != nx * ny");
  if (!(extent > 0)) throw RuntimeError("height field: extent must be > 0 m");
  HeightField f;
  f.params.nx = nx;
  f.params.ny = ny;
  f.params.extent = static_cast<float>(extent);
  f.params.min_depth = *std::min_element(depth.begin(), depth.end());
  f.params.max_depth = *std::max_element(depth.begin(), depth.end());
  // Enough cells for any ray that stays within a few field widths of the square; a steeper cap only
  // matters for near-horizontal sampling rays, which then end in the water where they stop.
  f.params.max_cells = 8 * (nx + ny) + 64;
  f.depth = std::move(depth);
  return f;
}

HeightField loadHeightField(const BottomDesc& bottom, DataFiles* files) {
  const Image img = readImageVia(files, bottom.heightfield);
  if (img.width < 2 || img.height < 2 || img.channels < 1) {
    throw RuntimeError("height-field bottom '" + bottom.heightfield + "': need a grey image of at least 2 x 2 pixels, got " +
                       std::to_string(img.width) + " x " + std::to_string(img.height));
  }
  std::vector<float> depth(img.pixelCount());
  for (int j = 0; j < img.height; ++j) {
    for (int i = 0; i < img.width; ++i) {
      double g = img.at(i, j, 0);
      if (img.channels >= 3) g = (img.at(i, j, 0) + img.at(i, j, 1) + img.at(i, j, 2)) / 3.0;
      if (!std::isfinite(g)) {
        throw RuntimeError("height-field bottom '" + bottom.heightfield + "': pixel (" + std::to_string(i) + ", " +
                           std::to_string(j) + ") is not finite");
      }
      g = std::clamp(g, 0.0, 1.0);
      depth[static_cast<size_t>(j) * img.width + i] =
          static_cast<float>(bottom.max_depth + g * (bottom.min_depth - bottom.max_depth));
    }
  }
  return makeHeightField(img.width, img.height, bottom.extent, std::move(depth));
}

double heightFieldBytes(const HeightField& field) {
  return double(sizeof(SeaHeightField)) + double(sizeof(float)) * double(field.depth.size());
}

HeightFieldBuffers uploadHeightField(Device& device, const HeightField& field) {
  HeightFieldBuffers b;
  onDevice("height-field floor upload", [&] {
    b.params = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(SeaHeightField),
                          const_cast<SeaHeightField*>(&field.params));
    b.depth = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(float) * field.depth.size(),
                         const_cast<float*>(field.depth.data()));
  });
  return b;
}

namespace {

fs::path tableDir() { return fs::path(cacheDir("sea_depth_tables")); }

}  // namespace

std::optional<std::vector<float>> loadDepthTable(uint64_t key, size_t count) {
  // The cache first, then the kernel store (device/kernel_store.h: the shipped scenes' tables).
  const std::string name = hex64(key) + ".f32";
  std::error_code ec;
  fs::path p;
  for (const std::string& dir : {tableDir().string(), storedDepthTableDir()})
    if (!dir.empty() && fs::exists(fs::path(dir) / name, ec)) {
      p = fs::path(dir) / name;
      break;
    }
  if (p.empty() || fs::file_size(p, ec) != count * sizeof(float)) return std::nullopt;
  std::vector<float> table(count);
  std::ifstream in(p, std::ios::binary);
  if (!in.read(reinterpret_cast<char*>(table.data()), static_cast<std::streamsize>(count * sizeof(float)))) {
    return std::nullopt;
  }
  for (float v : table)
    if (!std::isfinite(v) || v < 0) return std::nullopt;  // not ours, or damaged: recompute
  return table;
}

void storeDepthTable(uint64_t key, const std::vector<float>& table) {
  const fs::path dir = tableDir();
  if (dir.empty()) return;
  try {
    writeFileAtomic((dir / (hex64(key) + ".f32")).string(),
                    [&](const std::string& tmp) { writeBytes(tmp, table.data(), table.size() * sizeof(float)); });
  } catch (const RuntimeError&) {
    // Best effort: the table is recomputed next time.
  }
}

}  // namespace seasim
