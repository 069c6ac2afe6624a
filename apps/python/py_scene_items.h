#pragma once
// The identities of a scene's objects and lights, as Python sees them: a view
// (scene.objects[2]) holds its item's identity, not its position, so it follows the item when
// other items are inserted or removed, as a Python reference follows its object. An item that
// leaves its list (removed, or replaced by an assignment) keeps what it was for the views that
// still hold it: they read, and copy, as that item (so `a[1], a[2] = a[2], a[1]` swaps) but
// refuse edits, naming how it left.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace nxpy {

/// The identity of one item, shared by its views.
template <class Desc>
struct ItemIdentity {
  uint64_t id = 0;
  std::optional<Desc> former; ///< what the item was when it left its list (else empty)
  std::string leftAs;         ///< its label then ("objects[3]")
  std::string how;            ///< the edit it left by ("del objects[3]")
};

/// The identities of one list's items, in list order, and those views hold.
template <class Desc>
class ItemRegistry {
public:
  ItemRegistry() = default;
  /// A copied scene's items get the same identities; the copy's views are its own.
  ItemRegistry(const ItemRegistry& o) : ids_(o.ids_), next_(o.next_) {}
  ItemRegistry& operator=(const ItemRegistry& o) {
    ids_ = o.ids_, next_ = o.next_, held_.clear();
    return *this;
  }

  /// The identity of the item at position i of a list of n items (a list read from a file or a
  /// dict gets its identities here, at its first view).
  std::shared_ptr<ItemIdentity<Desc>> at(size_t i, size_t n) {
    sync(n);
    const uint64_t id = ids_[i];
    if (auto it = held_.find(id); it != held_.end())
      if (auto h = it->second.lock()) return h;
    auto h = std::make_shared<ItemIdentity<Desc>>();
    h->id = id;
    held_[id] = h;
    return h;
  }

  /// Where the item with identity `id` is now, if it is still in the list.
  std::optional<size_t> position(uint64_t id, size_t n) {
    sync(n);
    for (size_t i = 0; i < ids_.size(); ++i)
      if (ids_[i] == id) return i;
    return std::nullopt;
  }

  /// A new item at position i (the list had n items before).
  void inserted(size_t i, size_t n) {
    sync(n);
    ids_.insert(ids_.begin() + static_cast<std::ptrdiff_t>(i), next_++);
  }

  /// The item at position i of n leaves the list (removed: `removed`, else replaced by a new
  /// item): views holding it keep a copy of `d`.
  void leaving(size_t i, size_t n, const Desc& d, const std::string& label, const std::string& how,
               bool removed) {
    sync(n);
    const uint64_t id = ids_[i];
    if (auto it = held_.find(id); it != held_.end()) {
      if (auto h = it->second.lock()) h->former = d, h->leftAs = label, h->how = how;
      held_.erase(it);
    }
    if (removed)
      ids_.erase(ids_.begin() + static_cast<std::ptrdiff_t>(i));
    else
      ids_[i] = next_++;
  }

private:
  void sync(size_t n) {
    while (ids_.size() < n) ids_.push_back(next_++);
    if (ids_.size() > n) ids_.resize(n);
    // views no longer held need no entry
    if (held_.size() > 64 && held_.size() > 2 * n)
      for (auto it = held_.begin(); it != held_.end();)
        it = it->second.expired() ? held_.erase(it) : std::next(it);
  }

  std::vector<uint64_t> ids_;
  uint64_t next_ = 1;
  std::unordered_map<uint64_t, std::weak_ptr<ItemIdentity<Desc>>> held_;
};

} // namespace nxpy
