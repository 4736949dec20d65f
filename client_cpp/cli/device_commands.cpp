// felt touch, grab, record and replay: a haptic device emulator that drives a proxy at haptic
// rate along a scripted path (the server's own DevicePath, so scripts mean the same on both
// sides) and logs what the server answers.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <mutex>
#include <thread>

#include "cli/command_errors.hpp"
#include "cli/commands.hpp"
#include "cli/csv_path.hpp"
#include "cli/first_error.hpp"
#include "cli/progress.hpp"
#include "device/device_path.hpp"
#include "device/haptic_recording.hpp"
#include "local_renderer.hpp"

namespace felt::cli {

namespace v1 = felt::v1;
using client::ClientError;

namespace {

using Clock = std::chrono::steady_clock;

Eigen::Vector3d vec(const std::vector<double>& v) {
  return {v[0], v[1], v[2]};
}
Eigen::Vector3d vec(const v1::Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

/// One update the emulator sent and what came back for it.
struct Sample {
  double time = 0;  ///< s, of the path
  DeviceSample device;
  std::uint64_t sent_us = 0;
  std::optional<v1::ForceUpdate> reply;
  double round_trip_us = 0;
};

void put(const Vec3& v, v1::Vec3& out) {
  out.set_x(v.x());
  out.set_y(v.y());
  out.set_z(v.z());
}

/// The ProxyUpdate of proxy `proxy` for sample `s`.
v1::ClientMessage update_message(std::uint32_t proxy, const Sample& s) {
  v1::ClientMessage message;
  v1::ProxyUpdate& update = *message.mutable_proxy_update();
  update.set_proxy_id(proxy);
  put(s.device.position, *update.mutable_position());
  update.set_buttons(s.device.buttons);
  update.set_client_time_us(s.sent_us);
  return message;
}

/// Waits until `times[k]` after `start`, and makes sample k: the path there, stamped with the
/// steady clock. The stamp identifies a reply: two updates in the same microsecond would share
/// one, so each is later than the one before.
Sample& tick(const DevicePath& path, const std::vector<double>& times, std::size_t k,
             Clock::time_point start, std::vector<Sample>& samples) {
  std::this_thread::sleep_until(
      start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(times[k])));
  Sample& s = samples[k];
  s.time = times[k];
  s.device = path.at(times[k]);
  s.sent_us = client::steady_microseconds();
  if (k > 0 && s.sent_us <= samples[k - 1].sent_us) s.sent_us = samples[k - 1].sent_us + 1;
  return s;
}

DevicePath make_path(const DeviceOptions& o) {
  const auto need = [](const std::vector<double>& v, const char* flag) {
    if (v.size() != 3) throw UsageError(std::string(flag) + " X,Y,Z is needed");
  };
  DevicePath path;
  path.period = o.period;
  path.buttons = o.buttons;
  if (o.path == "line" || o.path == "press") {
    need(o.from, "--from");
    need(o.to, "--to");
    path.shape = o.path == "line" ? DevicePath::Shape::kLine : DevicePath::Shape::kPress;
    path.a = vec(o.from);
    path.b = vec(o.to);
  } else if (o.path == "circle") {
    need(o.center, "--center");
    path.shape = DevicePath::Shape::kCircle;
    path.a = vec(o.center);
    path.axis = vec(o.axis);
    path.radius = o.radius;
    if (path.axis.norm() == 0) throw UsageError("--axis must not be 0");
  } else if (o.path == "csv") {
    path = read_csv_path(o.csv);
  } else {
    throw UsageError("--path must be line, circle, press or csv");
  }
  if (!(o.period > 0)) throw UsageError("--period must be > 0");
  return path;
}

double path_duration(const DeviceOptions& o, const DevicePath& path) {
  if (o.duration > 0) return o.duration;
  if (path.shape == DevicePath::Shape::kSamples) return path.samples.back().time;
  return path.shape == DevicePath::Shape::kPress ? path.period + 1 : path.period;
}

/// Sends `path` at `times` (s after the start) as updates of proxy `proxy` and waits for the
/// replies; each sample has its reply, if one came. The first Error the server sends (a refused
/// update, or why it closed the connection) stops the device and is thrown as a ClientError.
std::vector<Sample> drive(const Common& common, const DevicePath& path,
                          const std::vector<double>& times, std::uint32_t proxy,
                          const char* label) {
  std::mutex mutex;
  std::vector<std::pair<v1::ForceUpdate, std::uint64_t>> replies;
  FirstError error;
  client::AsyncClient client;
  client.on_force([&](const v1::ForceUpdate& force, std::uint64_t received_us) {
    std::lock_guard lock(mutex);
    replies.emplace_back(force, received_us);
  });
  client.on_error([&](const v1::Error& e) { error.keep(e); });
  connect(client, common, "felt-device");
  std::vector<Sample> samples(times.size());
  Progress progress(label, times.empty() ? 0 : times.back());
  const Clock::time_point start = Clock::now();
  for (std::size_t k = 0; k < times.size() && !error.any(); ++k) {
    const Sample& s = tick(path, times, k, start, samples);
    client.send(update_message(proxy, s));
    progress.update(times[k]);
  }
  progress.finish();
  const auto deadline = Clock::now() + std::chrono::seconds(2);
  while (Clock::now() < deadline && !error.any()) {
    {
      std::lock_guard lock(mutex);
      if (replies.size() >= times.size()) break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  client.close();
  error.throw_if_any();
  std::lock_guard lock(mutex);
  // replies come back in order; match them to their updates by the echoed stamp
  std::size_t k = 0;
  for (const auto& [force, received_us] : replies) {
    while (k < samples.size() && samples[k].sent_us < force.client_time_us()) ++k;
    if (k == samples.size()) break;
    if (samples[k].sent_us == force.client_time_us()) {
      samples[k].reply = force;
      samples[k].round_trip_us = static_cast<double>(received_us - samples[k].sent_us);
    }
  }
  return samples;
}

/// The device's side of a local-model proxy (docs/protocol.md 7.5): opens a proxy asking for
/// a local model, renders `path` at `times` against it with LocalRenderer, and sends the device
/// and what it felt upstream every rate/upstream_rate ticks. Each sample's reply is what the
/// device rendered at that tick, and its round trip the last one measured upstream. While the
/// server says a vertex is held (grabbing is resolved there), the device renders the server's
/// grab force.
std::vector<Sample> drive_local(const Common& common, const DevicePath& path,
                                const std::vector<double>& times, const DeviceOptions& o,
                                const char* label) {
  if (!(o.upstream_rate >= 1 && o.upstream_rate <= o.rate)) {
    throw ClientError(v1::ERROR_CODE_BAD_REQUEST, "--upstream-rate must be 1 Hz to --rate");
  }
  struct Mailbox {
    std::mutex mutex;
    std::optional<std::pair<LocalModel, double>> model;  ///< and the time it shows
    double round_trip_us = 0;
    std::optional<v1::ForceUpdate> latest;  ///< without its model
    std::size_t dropped = 0;                ///< malformed models
  } box;
  FirstError error;
  client::AsyncClient client;
  client.on_force([&](const v1::ForceUpdate& force, std::uint64_t received_us) {
    const double round_trip = static_cast<double>(received_us - force.client_time_us()) * 1e-6;
    std::optional<LocalModel> model;
    if (force.has_local_model()) model = client::local_model_from(force.local_model());
    v1::ForceUpdate latest = force;
    latest.clear_local_model();
    std::lock_guard lock(box.mutex);
    box.latest = std::move(latest);
    box.round_trip_us = round_trip * 1e6;
    if (model) {
      const double shows = client::local_model_time(
          force.local_model(), static_cast<double>(received_us) * 1e-6, round_trip);
      box.model.emplace(std::move(*model), shows);
    } else if (force.has_local_model()) {
      ++box.dropped;
    }
  });
  client.on_error([&](const v1::Error& e) { error.keep(e); });
  connect(client, common, "felt-device");
  v1::ClientMessage open;
  open.mutable_open_proxy()->mutable_local_model()->set_radius(o.model_radius);
  const v1::ProxyOpened opened = client.request(open).proxy_opened();
  client::LocalRenderer renderer(opened.settings(), {o.device_damping, 1 / o.rate});
  const auto every = static_cast<std::size_t>(std::max(1.0, std::round(o.rate / o.upstream_rate)));

  std::vector<Sample> samples(times.size());
  Progress progress(label, times.empty() ? 0 : times.back());
  const Clock::time_point start = Clock::now();
  for (std::size_t k = 0; k < times.size() && !error.any(); ++k) {
    Sample& s = tick(path, times, k, start, samples);
    std::optional<v1::ForceUpdate> latest;
    {
      std::lock_guard lock(box.mutex);
      if (box.model) {
        renderer.take(box.model->first, box.model->second, box.round_trip_us * 1e-6);
        box.model.reset();
      }
      latest = box.latest;
      s.round_trip_us = box.round_trip_us;
    }
    const client::LocalForce felt =
        renderer.tick(s.device.position, static_cast<double>(s.sent_us) * 1e-6);
    v1::ForceUpdate& rendered = s.reply.emplace();
    const HapticContact& c = felt.contact;
    const bool grabbing = latest && latest->grabbing();
    const Vec3 force = grabbing ? vec(latest->force()) : c.force;
    rendered.set_proxy_id(opened.proxy_id());
    put(force, *rendered.mutable_force());
    rendered.set_in_contact(c.in_contact);
    rendered.set_body_id(grabbing ? latest->body_id() : c.body_id);
    rendered.set_triangle(c.triangle);
    put(c.contact_point, *rendered.mutable_contact_point());
    put(c.proxy, *rendered.mutable_proxy());
    rendered.set_grabbing(grabbing);
    if (grabbing) rendered.set_grabbed_vertex(latest->grabbed_vertex());
    if (k % every == 0) {
      v1::ClientMessage message = update_message(opened.proxy_id(), s);
      *message.mutable_proxy_update()->mutable_local() = renderer.upstream();
      client.send(std::move(message));
    }
    progress.update(times[k]);
  }
  progress.finish();
  client.close();
  error.throw_if_any();
  if (box.dropped > 0) std::printf("%zu malformed local models dropped\n", box.dropped);
  return samples;
}

std::vector<double> ticks(double duration, double rate) {
  std::vector<double> times;
  const auto count = static_cast<std::size_t>(std::floor(duration * rate)) + 1;
  for (std::size_t k = 0; k < count; ++k) times.push_back(static_cast<double>(k) / rate);
  return times;
}

double percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const auto at = static_cast<std::size_t>(std::ceil(p * static_cast<double>(values.size()))) - 1;
  return values[std::min(at, values.size() - 1)];
}

void write_log(const std::string& file, const std::vector<Sample>& samples) {
  std::ofstream out(file);
  out << "time,x,y,z,buttons,fx,fy,fz,in_contact,body,triangle,contact_x,contact_y,contact_z,"
         "grabbing,round_trip_us,proxy_x,proxy_y,proxy_z\n";
  out.precision(9);
  for (const Sample& s : samples) {
    if (!s.reply) continue;
    const v1::ForceUpdate& r = *s.reply;
    out << s.time << "," << s.device.position.x() << "," << s.device.position.y() << ","
        << s.device.position.z() << "," << s.device.buttons << "," << r.force().x() << ","
        << r.force().y() << "," << r.force().z() << "," << r.in_contact() << "," << r.body_id()
        << "," << r.triangle() << "," << r.contact_point().x() << "," << r.contact_point().y()
        << "," << r.contact_point().z() << "," << r.grabbing() << "," << s.round_trip_us << ","
        << r.proxy().x() << "," << r.proxy().y() << "," << r.proxy().z() << "\n";
  }
  if (!out) throw LocalError("cannot write " + file);
}

void summarize(const std::vector<Sample>& samples) {
  std::vector<double> round_trips;
  std::size_t contact = 0, grabbing = 0;
  double max_force = 0;
  for (const Sample& s : samples) {
    if (!s.reply) continue;
    round_trips.push_back(s.round_trip_us);
    contact += s.reply->in_contact() ? 1 : 0;
    grabbing += s.reply->grabbing() ? 1 : 0;
    max_force = std::max(max_force, vec(s.reply->force()).norm());
  }
  std::printf("%zu updates sent, %zu answered, %zu in contact, %zu grabbing, max |F| %.4g N\n",
              samples.size(), round_trips.size(), contact, grabbing, max_force);
  std::printf("round trip: p50 %.0f us, p99 %.0f us, max %.0f us\n", percentile(round_trips, 0.5),
              percentile(round_trips, 0.99), percentile(round_trips, 1.0));
  for (auto it = samples.rbegin(); it != samples.rend(); ++it) {
    if (!it->reply) continue;
    const v1::ForceUpdate& r = *it->reply;
    std::printf("last: force %.6g %.6g %.6g N, %s", r.force().x(), r.force().y(), r.force().z(),
                r.in_contact() ? "in contact" : "free");
    if (r.in_contact()) std::printf(" with body %u, triangle %d", r.body_id(), r.triangle());
    if (r.grabbing()) std::printf(", holding vertex %u", r.grabbed_vertex());
    std::printf("\n");
    break;
  }
}

int single_touch(const Common& common, const DeviceOptions& o) {
  client::Client client;
  connect(client, common);
  const v1::ForceUpdate force =
      client.proxy_update(o.proxy, {o.at[0], o.at[1], o.at[2]}, o.buttons);
  std::printf("force %.6g %.6g %.6g N  |F| %.6g N\n", force.force().x(), force.force().y(),
              force.force().z(), vec(force.force()).norm());
  if (force.in_contact()) {
    std::printf("contact at %.6g %.6g %.6g on body %u, triangle %d\n", force.contact_point().x(),
                force.contact_point().y(), force.contact_point().z(), force.body_id(),
                force.triangle());
  } else {
    std::printf("no contact\n");
  }
  return 0;
}

}  // namespace

int touch(const Common& common, const DeviceOptions& o) {
  if (!o.at.empty()) {
    if (o.local_model) {
      throw ClientError(v1::ERROR_CODE_BAD_REQUEST, "--local-model renders a --path, not --at");
    }
    return single_touch(common, o);
  }
  if (!(o.rate >= 1 && o.rate <= 10'000)) {
    throw UsageError("--rate must be 1 to 10000 Hz");
  }
  const DevicePath path = make_path(o);
  const std::vector<double> times = ticks(path_duration(o, path), o.rate);
  const auto samples = o.local_model ? drive_local(common, path, times, o, "touch")
                                     : drive(common, path, times, o.proxy, "touch");
  if (!o.log.empty()) write_log(o.log, samples);
  summarize(samples);
  return 0;
}

int grab(const Common& common, DeviceOptions o) {
  // press into the surface from --from to --to holding the grab button, then hold
  if (o.path.empty()) o.path = "press";
  o.buttons |= 1u;
  return touch(common, o);
}

int record(const Common& common, const DeviceOptions& o, const std::string& out_file) {
  const DevicePath path = make_path(o);
  const auto samples =
      drive(common, path, ticks(path_duration(o, path), o.rate), o.proxy, "record");
  std::ofstream out(out_file);
  write_recording_header(out);
  std::size_t written = 0;
  for (const Sample& s : samples) {
    if (!s.reply) continue;
    HapticRecord r;
    r.time = s.time;
    r.position = s.device.position;
    r.buttons = s.device.buttons;
    r.in_contact = s.reply->in_contact();
    r.body = s.reply->body_id();
    r.triangle = s.reply->triangle();
    r.proxy = vec(s.reply->proxy());
    r.force = vec(s.reply->force());
    write_record(out, r);
    ++written;
  }
  if (!out) throw LocalError("cannot write " + out_file);
  std::printf("%zu updates recorded to %s\n", written, out_file.c_str());
  summarize(samples);
  return 0;
}

int replay(const Common& common, const std::string& file, double tolerance) {
  std::ifstream in(file);
  auto records = in ? read_recording(in) : std::unexpected(std::string("cannot open the file"));
  if (!records) throw UsageError(file + ": " + records.error());
  if (records->empty()) throw UsageError(file + ": no records");
  DevicePath path;
  path.shape = DevicePath::Shape::kSamples;
  std::vector<double> times;
  std::vector<std::size_t> record_of;  // a recording of several devices: the first one's
  for (std::size_t k = 0; k < records->size(); ++k) {
    const HapticRecord& r = (*records)[k];
    if (r.device != (*records)[0].device) continue;
    path.samples.push_back({r.time, r.position, r.buttons});
    times.push_back(r.time);
    record_of.push_back(k);
  }
  const auto samples = drive(common, path, times, 0, "replay");
  std::size_t compared = 0, equivalent = 0;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    if (!samples[k].reply) continue;
    const HapticRecord& recorded = (*records)[record_of[k]];
    HapticRecord replayed = recorded;
    replayed.in_contact = samples[k].reply->in_contact();
    replayed.body = samples[k].reply->body_id();
    replayed.triangle = samples[k].reply->triangle();
    replayed.proxy = vec(samples[k].reply->proxy());
    ++compared;
    equivalent += collision_equivalent(recorded, replayed, tolerance) ? 1 : 0;
  }
  std::printf("replay: %zu of %zu updates collision-equivalent to the recording (tolerance %g m)\n",
              equivalent, compared, tolerance);
  summarize(samples);
  return 0;
}

}  // namespace felt::cli
