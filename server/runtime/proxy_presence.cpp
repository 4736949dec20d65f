#include "runtime/proxy_presence.hpp"

#include <algorithm>

namespace felt {

void ProxyPresence::update(const ProxyPresenceEntry& entry) {
  std::lock_guard lock(mutex_);
  const auto it = std::find_if(entries_.begin(), entries_.end(),
                               [&](const ProxyPresenceEntry& e) { return e.key == entry.key; });
  if (it != entries_.end()) {
    *it = entry;
  } else {
    entries_.push_back(entry);
  }
}

void ProxyPresence::forget(ProxyKey key) {
  std::lock_guard lock(mutex_);
  std::erase_if(entries_, [key](const ProxyPresenceEntry& e) { return e.key == key; });
}

std::vector<ProxyPresenceEntry> ProxyPresence::since(
    std::chrono::steady_clock::time_point since) const {
  std::vector<ProxyPresenceEntry> out;
  std::lock_guard lock(mutex_);
  for (const ProxyPresenceEntry& e : entries_) {
    if (e.updated >= since) out.push_back(e);
  }
  return out;
}

}  // namespace felt
