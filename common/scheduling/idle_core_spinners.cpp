#include "scheduling/idle_core_spinners.hpp"

#include <pthread.h>
#include <sched.h>

#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

#include "scheduling/thread_name.hpp"

namespace felt {
namespace {

/// Pauses between two looks at the clock: a few microseconds.
constexpr int kPausesPerLook = 64;

void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  // PAUSE leaves the pipeline to a sibling hyperthread and tells a hypervisor this is a spin
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}

}  // namespace

std::expected<std::unique_ptr<IdleCoreSpinners>, std::string> IdleCoreSpinners::start(
    std::chrono::milliseconds linger) {
  if (linger.count() <= 0) {
    return std::unexpected("idle cores spin for " + std::to_string(linger.count()) +
                           " ms after a touch: it must be more than 0");
  }
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof allowed, &allowed) != 0) {
    return std::unexpected(std::string("sched_getaffinity: ") + std::strerror(errno));
  }
  std::unique_ptr<IdleCoreSpinners> spinners(new IdleCoreSpinners(linger));
  spinners->threads_.reserve(CPU_COUNT(&allowed));
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu) {
    if (!CPU_ISSET(cpu, &allowed)) continue;
    // a spinner sleeps until the first touch, so it never spins before it is pinned and idle
    try {
      spinners->threads_.emplace_back(
          [raw = spinners.get()](std::stop_token stop) { raw->spin(stop); });
    } catch (const std::system_error& e) {
      return std::unexpected("starting the spinner of core " + std::to_string(cpu) + ": " +
                             e.what());
    }
    std::jthread& thread = spinners->threads_.back();
    name_thread(thread.native_handle(), "felt-spin-" + std::to_string(cpu));
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(cpu, &one);
    sched_param param{};
    int error = pthread_setaffinity_np(thread.native_handle(), sizeof one, &one);
    const char* what = "pinning a spinner to core ";
    if (error == 0) {
      // lowering a thread's policy takes no privilege
      error = pthread_setschedparam(thread.native_handle(), SCHED_IDLE, &param);
      what = "SCHED_IDLE for the spinner of core ";
    }
    if (error == 0) {
      error = pthread_getcpuclockid(thread.native_handle(), &spinners->cpu_clocks_.emplace_back());
      what = "the CPU clock of the spinner of core ";
    }
    if (error != 0)
      return std::unexpected(what + std::to_string(cpu) + ": " + std::strerror(error));
  }
  return spinners;
}

IdleCoreSpinners::~IdleCoreSpinners() {
  for (std::jthread& thread : threads_) thread.request_stop();
  // the stop callbacks wake the sleepers; the jthreads join
  threads_.clear();
}

void IdleCoreSpinners::touch(Clock::time_point now) {
  last_touch_.store(now.time_since_epoch().count());
  // a spinner that goes to sleep counts itself before it looks at last_touch_ again, so
  // either it sees this touch or this sees it (both sequentially consistent)
  if (sleepers_.load() == 0) return;
  { std::lock_guard lock(mutex_); }
  wake_.notify_all();
}

void IdleCoreSpinners::spin_until_destroyed() {
  // a touch this far ahead is never lingered past (and now minus it does not overflow)
  touch(Clock::time_point(Clock::duration(std::numeric_limits<Clock::rep>::max() / 2)));
}

bool IdleCoreSpinners::lingering() const {
  return Clock::now().time_since_epoch().count() - last_touch_.load() <
         Clock::duration(linger_).count();
}

void IdleCoreSpinners::spin(std::stop_token stop) {
  while (!stop.stop_requested()) {
    if (lingering()) {
      for (int i = 0; i < kPausesPerLook; ++i) cpu_relax();
      continue;
    }
    std::unique_lock lock(mutex_);
    sleepers_.fetch_add(1);
    wake_.wait(lock, stop, [this] { return lingering(); });
    sleepers_.fetch_sub(1);
  }
}

std::chrono::nanoseconds IdleCoreSpinners::cpu_time() const {
  std::chrono::nanoseconds total{0};
  for (const clockid_t clock : cpu_clocks_) {
    timespec used{};
    if (clock_gettime(clock, &used) != 0) continue;
    total += std::chrono::seconds(used.tv_sec) + std::chrono::nanoseconds(used.tv_nsec);
  }
  return total;
}

}  // namespace felt
