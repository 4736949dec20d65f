#include "runtime/proxy_render.hpp"

#include "runtime/local_model_stiffness.hpp"

namespace felt {

ProxyOutput render_proxy(HapticProxy& proxy, const HapticFrame& frame, SteadyClock::time_point now,
                         Real time_scale, const Vec3& device, std::uint32_t buttons,
                         ReactionAccumulator& reactions, const LocalContact* local) {
  ProxyOutput out = proxy.update(frame.surface(now), proxy.seconds_since_last(now), device, buttons,
                                 reactions, local);
  LocalModelFeed* feed = proxy.local_model();
  if (feed && feed->due(frame.to->version, now)) {
    // the newer snapshot, the scene as it was when published, moving at the velocities of the
    // simulation at the scene's pace: not over the wall time between the two publications,
    // which a loaded machine makes in bursts (velocities 50 times too large, and a client's
    // extrapolation far off). Not when the server's own render reaches it, one interval later
    // (HapticFrame): after a stall of the physics thread that interval is the stall, and a
    // model dated that far ahead was moved back by its velocities on the client (up to 0.25 s:
    // a swinging curtain centimetres behind where it was, through the client's proxy).
    const Real stepped = frame.to->sim_time - frame.from->sim_time;
    const Vec3& centre = local ? local->proxy : out.contact.proxy;
    out.local_model = LocalModelCut{
        cut_local_model(frame.surface_at(1), time_scale > 0 ? stepped / time_scale : 0, centre,
                        feed->request().radius, kMaxLocalModelTriangles),
        frame.to->step, frame.published};
    LocalModel& model = out.local_model->model;
    model.push = out.local_push;
    set_local_model_stiffness(model, *frame.to, centre, local, out.pushed_body,
                              out.pushed_body_stiffness);
    feed->sent(frame.to->version, now);
  }
  return out;
}

}  // namespace felt
