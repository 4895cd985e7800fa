// resources.h — the frame's named resources (DESIGN.md "The renderer's shape"): G-buffer, radiance
// targets, shadow maps, froxel volume, ocean and caustic maps. Each is an object a pass publishes
// (usually the pass's own buffers) under the name the plan gives it.
//
// Two counters per resource drive the incremental updates (renderer.h):
//   generation — bumped when a new object is published (new buffers: readers set up again, since
//                their kernels hold the old buffers as arguments);
//   version    — bumped each time a pass writes it (readers run again).
// A pass sees resources only through a PassResources view that allows what its plan entry declares:
// reading an undeclared resource is an error, so the plan's reads/writes stay true.
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <typeindex>
#include <vector>

#include "util/error.h"

namespace seasim {

class Resources {
 public:
  struct Entry {
    std::shared_ptr<void> object;
    std::type_index type = typeid(void);
    uint64_t generation = 0;
    uint64_t version = 0;
  };

  template <class T>
  void publish(const std::string& name, std::shared_ptr<T> object) {
    Entry& e = entries_[name];
    e.object = std::move(object);
    e.type = typeid(T);
    e.generation = ++counter_;
    e.version = ++counter_;
  }
  // Records that a pass wrote the resource's contents.
  void touch(const std::string& name);
  bool has(const std::string& name) const { return entries_.count(name) != 0; }
  // Published and of type T.
  template <class T>
  bool holds(const std::string& name) const {
    const auto it = entries_.find(name);
    return it != entries_.end() && it->second.object && it->second.type == typeid(T);
  }
  // 0 when the resource has not been published.
  uint64_t generation(const std::string& name) const;
  uint64_t version(const std::string& name) const;

  template <class T>
  T& get(const std::string& name) const {
    const auto it = entries_.find(name);
    if (it == entries_.end() || !it->second.object) {
      throw RuntimeError("renderer: resource '" + name + "' was read before any pass published it");
    }
    if (it->second.type != typeid(T)) {
      throw RuntimeError("renderer: resource '" + name + "' holds another type than the reader expects");
    }
    return *static_cast<T*>(it->second.object.get());
  }
  void clear() { entries_.clear(); }

 private:
  std::map<std::string, Entry> entries_;
  uint64_t counter_ = 0;  // one counter: generations and versions only ever grow
};

// The resources one pass may touch: its plan entry's reads and writes.
class PassResources {
 public:
  PassResources(Resources& all, std::string pass, const std::vector<std::string>& reads,
                const std::vector<std::string>& writes)
      : all_(all), pass_(std::move(pass)), reads_(reads), writes_(writes) {}

  template <class T>
  T& read(const std::string& name) const {
    check(name, true);
    return all_.get<T>(name);
  }
  // The resource if published, else nullptr (optional inputs).
  template <class T>
  T* find(const std::string& name) const {
    check(name, true);
    return all_.has(name) ? &all_.get<T>(name) : nullptr;
  }
  template <class T>
  void publish(const std::string& name, std::shared_ptr<T> object) {
    check(name, false);
    all_.publish(name, std::move(object));
  }
  bool declaresRead(const std::string& name) const;
  // A declared read's version (Resources::version): bumped each time a pass writes it, so a reader
  // can keep what it made from the contents while they stay the same.
  uint64_t version(const std::string& name) const {
    check(name, true);
    return all_.version(name);
  }

 private:
  void check(const std::string& name, bool reading) const;
  Resources& all_;
  std::string pass_;
  const std::vector<std::string>& reads_;
  const std::vector<std::string>& writes_;
};

}  // namespace seasim
