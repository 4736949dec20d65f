#include "runtime/proxy_handle.hpp"

#include "runtime/scene_runner.hpp"

namespace felt {

ProxyHandle::~ProxyHandle() {
  if (scene_) scene_->close_proxy(proxy_);
}

ProxyOutput ProxyHandle::update(const Vec3& device, std::uint32_t buttons,
                                const LocalContact* local) {
  return scene_->render(proxy_, device, buttons, local);
}

}  // namespace felt
