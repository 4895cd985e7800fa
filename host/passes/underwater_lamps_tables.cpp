#include "passes/underwater_lamps_tables.h"

#include "underwater/lamps_bottom_glow.h"
#include "underwater/lamps_ms_table.h"
#include "underwater/lamps_ms_weights.h"

namespace seasim {

namespace {

// A table's inputs as bytes: equal bytes, equal table (plain structs and numbers only).
template <class T>
void put(std::string& key, const T& v) {
  key.append(reinterpret_cast<const char*>(&v), sizeof v);
}

template <class T>
void put(std::string& key, const std::vector<T>& v) {
  put(key, v.size());
  key.append(reinterpret_cast<const char*>(v.data()), sizeof(T) * v.size());
}

// Builds `t` with `build` when `key` differs from the one it was built for.
template <class F>
void refresh(LampsOrdersTables::Table& t, std::string& built_for, std::string key, F build) {
  if (t.generation > 0 && key == built_for) return;
  t.values = build();
  ++t.generation;
  built_for = std::move(key);
}

}  // namespace

const LampsOrdersTables::Table& LampsOrdersTables::profiles(const std::vector<UwLamp>& lamps, double g, double beta,
                                                            int orders) {
  std::string key;
  put(key, lamps);
  put(key, g);
  put(key, beta);
  put(key, orders);
  refresh(profiles_, profiles_key_, std::move(key), [&] { return lampMsTable(lamps, g, beta, orders); });
  return profiles_;
}

const LampsOrdersTables::Table& LampsOrdersTables::glow(const std::vector<UwLamp>& lamps, const UwParams& params,
                                                        const std::vector<UwBand>& bands, double s_min) {
  std::string key;
  put(key, lamps);
  put(key, params.bottom_depth);
  put(key, bands);
  put(key, s_min);
  refresh(glow_, glow_key_, std::move(key), [&] { return lampBottomGlowTable(lamps, params, bands, s_min); });
  return glow_;
}

const LampsOrdersTables::Table& LampsOrdersTables::weights(const std::vector<UwBand>& bands, double g, double kappa,
                                                           int orders) {
  std::string key;
  put(key, bands);
  put(key, g);
  put(key, kappa);
  put(key, orders);
  refresh(weights_, weights_key_, std::move(key), [&] { return lampMsWeights(bands, g, kappa, orders); });
  return weights_;
}

}  // namespace seasim
