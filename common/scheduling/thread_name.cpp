#include "scheduling/thread_name.hpp"

#include <algorithm>
#include <array>

namespace felt {

bool name_thread(pthread_t thread, std::string_view name) {
  std::array<char, kMaxThreadName + 1> cut{};
  std::copy_n(name.begin(), std::min(name.size(), kMaxThreadName), cut.begin());
  return pthread_setname_np(thread, cut.data()) == 0;
}

}  // namespace felt
