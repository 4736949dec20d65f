// felt watch: frames to a series of OBJ, PLY or VTK files.

#include <cstdio>
#include <iostream>

#include "cli/command_errors.hpp"
#include "cli/commands.hpp"
#include "cli/progress.hpp"
#include "frame_writers.hpp"

namespace felt::cli {

int watch(const Common& common, const WatchOptions& options) {
  client::MeshFormat format;
  if (!client::parse_mesh_format(options.format, format)) {
    throw UsageError("--format must be obj, ply or vtk");
  }
  client::Client client;
  connect(client, common);
  std::filesystem::create_directories(options.out_dir);
  client::FrameSubscription subscription;
  subscription.max_rate_hz = options.rate;
  subscription.normals = options.normals;
  subscription.body_ids = options.bodies;
  subscription.quantized = options.quantized || options.deltas;
  subscription.deltas = options.deltas;
  client.subscribe_frames(subscription);
  client::FrameAssembler assembler;
  std::vector<std::pair<double, std::string>> series;
  std::uint64_t bytes = 0, skipped = 0;
  Progress progress("watch", options.frames);
  for (int i = 0; i < options.frames; ++i) {
    const auto frame = client.next_frame(std::chrono::seconds(5));
    if (!frame) {
      std::cerr << "felt: no frame within 5 s\n";
      return 1;
    }
    bytes += frame->ByteSizeLong();
    skipped += frame->skipped();
    const auto decoded = assembler.assemble(*frame);
    if (!decoded) {
      std::cerr << "felt: " << decoded.error() << "\n";
      return 1;
    }
    if (options.deltas) client.ack_frame_async(frame->sequence());
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d%s", i, client::mesh_extension(format));
    const auto file = std::filesystem::path(options.out_dir) / name;
    if (!client::write_frame(file, *decoded, format)) {
      std::cerr << "felt: cannot write " << file << "\n";
      return 1;
    }
    series.emplace_back(decoded->sim_time, name);
    progress.update(i + 1, "step " + std::to_string(frame->step()));
  }
  progress.finish();
  if (format == client::MeshFormat::kVtk) {
    const auto pvd = std::filesystem::path(options.out_dir) / "frames.pvd";
    if (!client::write_pvd(pvd, series)) {
      std::cerr << "felt: cannot write " << pvd << "\n";
      return 1;
    }
    std::printf("%s: open it in ParaView\n", pvd.c_str());
  }
  std::printf("%d frames in %s, %.1f kB a frame on the wire, %llu skipped by the server\n",
              options.frames, options.out_dir.c_str(), bytes / 1e3 / options.frames,
              static_cast<unsigned long long>(skipped));
  return 0;
}

}  // namespace felt::cli
