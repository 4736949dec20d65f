#include "runtime/scripted_devices.hpp"

#include <ostream>
#include <string>

namespace felt {

std::vector<ScriptedDevice> devices_from_recording(const std::vector<HapticRecord>& records) {
  std::vector<ScriptedDevice> devices;
  for (const HapticRecord& r : records) {
    if (r.device >= devices.size()) devices.resize(r.device + 1);
    ScriptedDevice& device = devices[r.device];
    device.name = "recorded " + std::to_string(r.device);
    device.path.shape = DevicePath::Shape::kSamples;
    device.path.samples.push_back({r.time, r.position, r.buttons});
  }
  return devices;
}

ScriptedDevices::ScriptedDevices(const std::vector<ScriptedDevice>& devices,
                                 const ProxySettings& settings)
    : devices_(devices), latest_(devices.size()) {
  proxies_.reserve(devices.size());
  for (std::size_t i = 0; i < devices.size(); ++i) {
    latest_[i].device = static_cast<std::uint32_t>(i);
    proxies_.emplace_back(ProxyKey{0, latest_[i].device}, settings);
  }
}

void ScriptedDevices::tick(const HapticSurface& surface, Real t, Real dt,
                           ReactionAccumulator& reactions) {
  for (std::size_t i = 0; i < devices_.size(); ++i) {
    const DeviceSample device = devices_[i].path.at(t);
    const ProxyOutput out =
        proxies_[i].update(surface, dt, device.position, device.buttons, reactions);
    HapticRecord& r = latest_[i];
    r.time = t;
    r.position = device.position;
    r.buttons = device.buttons;
    r.in_contact = out.contact.in_contact;
    r.body = out.grabbing ? out.grabbed_body : out.contact.body_id;
    r.triangle = out.contact.triangle;
    r.proxy = out.contact.proxy;
    r.force = out.contact.force;
    if (recording_) write_record(*recording_, r);
  }
}

void ScriptedDevices::record_to(std::ostream* out) {
  recording_ = out;
  if (recording_) write_recording_header(*recording_);
}

void ScriptedDevices::close(ReactionAccumulator& reactions) const {
  for (const HapticProxy& proxy : proxies_) reactions.forget(proxy.key());
}

}  // namespace felt
