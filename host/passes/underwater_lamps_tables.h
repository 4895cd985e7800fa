// underwater_lamps_tables.h — the "orders" model's host tables (the lamps' blurred profiles, the bottom's
// glow, the orders' weights: underwater/lamps_ms_table.h, lamps_bottom_glow.h, lamps_ms_weights.h), kept
// by the lamps' frame-graph node across passes made anew when only the camera moved (the preview, an
// animation, a job's items): each is rebuilt only when its own inputs changed, and counts its builds so a
// pass uploads only what is new.
#pragma once
#include <string>
#include <vector>

extern "C" {
#include "common/underwater_lamps_params.h"
#include "common/underwater_params.h"
}

namespace seasim {

class LampsOrdersTables {
 public:
  struct Table {
    std::vector<float> values;
    int generation = 0;  // how many times it was built
  };
  // lampMsTable(lamps, g, beta, orders).
  const Table& profiles(const std::vector<UwLamp>& lamps, double g, double beta, int orders);
  // lampBottomGlowTable(lamps, params, bands, s_min).
  const Table& glow(const std::vector<UwLamp>& lamps, const UwParams& params, const std::vector<UwBand>& bands,
                    double s_min);
  // lampMsWeights(bands, g, kappa, orders).
  const Table& weights(const std::vector<UwBand>& bands, double g, double kappa, int orders);

 private:
  Table profiles_, glow_, weights_;
  std::string profiles_key_, glow_key_, weights_key_;
};

}  // namespace seasim
