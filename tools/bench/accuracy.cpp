#include "accuracy.hpp"

#include <cmath>
#include <cstdint>

#include "support/reference/spec_scenes.hpp"

namespace ff::bench {

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Direction {
  reference::DVec d;
  Vec2 f;
  double degrees;
};

std::vector<Direction> directions() {
  std::vector<Direction> out;
  for (int k = 0; k < kDirections; ++k) {
    const double angle = 2.0 * kPi * k / kDirections;
    const reference::DVec d{std::cos(angle), std::sin(angle)};
    out.push_back({d, Vec2{static_cast<float>(d.x), static_cast<float>(d.y)}, 360.0 * k / kDirections});
  }
  return out;
}

}  // namespace

reference::ReferenceScene reference_scene_for(SceneId id) {
  namespace spec = reference::spec;
  switch (id) {
    case SceneId::Neutral: return reference::ReferenceScene(spec::neutral(), reference::kEveryPixel);
    case SceneId::FrictionmapTop: return reference::ReferenceScene(spec::frictionmap(-200.0), reference::kEveryPixel);
    case SceneId::HeightmapTop: return reference::ReferenceScene(spec::heightmap(-200.0), reference::kEveryPixel);
    case SceneId::HeightmapMiddle: return reference::ReferenceScene(spec::heightmap(0.0), reference::kEveryPixel);
    case SceneId::HeightmapBottom: return reference::ReferenceScene(spec::heightmap(200.0), reference::kEveryPixel);
    case SceneId::TunnelPilotA: return reference::ReferenceScene(spec::steering_tunnel(1.0), reference::kEveryPixel);
    case SceneId::TunnelPilotB: return reference::ReferenceScene(spec::steering_tunnel(10.0), reference::kEveryPixel);
    case SceneId::PilotCTop: return reference::ReferenceScene(spec::pilot_c(-200.0), reference::kEveryPixel);
    case SceneId::BumpMap: return reference::ReferenceScene(spec::bump_map(), reference::kEveryPixel);
    case SceneId::Vortex: return reference::ReferenceScene(spec::vortex(), reference::kEveryPixel);
    case SceneId::FamiliarisationPath:
      return reference::ReferenceScene(spec::familiarisation_path(), reference::kEveryPixel);
    case SceneId::General1:
    case SceneId::General3:
    case SceneId::General6:
    case SceneId::kCount: break;
  }
  return reference::ReferenceScene(scene_definition(id), reference::kEveryPixel);
}

ReferenceGrid::ReferenceGrid(const reference::ReferenceScene& scene, double step_px) : scene_(scene) {
  max_g_ = scene_.max_gradient();
  for (double y = 0.5; y <= 479.0; y += step_px) {
    for (double x = 0.5; x <= 799.0; x += step_px) points_.push_back({x, y});
  }
  for (const reference::DVec& p : points_) {
    if (scene_.rendering() == Rendering::Directional) {
      field_.push_back(scene_.field(p.x, p.y));
    } else {
      value_.push_back(scene_.raw_amplitude(p.x, p.y, 0.0, 0.0));
    }
  }
}

Accuracy ReferenceGrid::measure(const ScenePlan& plan) const {
  static const std::vector<Direction> kDirs = directions();
  Accuracy acc;
  double sum_sq = 0.0;
  constexpr double kBinLsb = 0.01;
  std::vector<uint32_t> histogram(static_cast<size_t>(4096.0 / kBinLsb) + 2, 0u);
  auto record = [&](double error_lsb, const reference::DVec& p, double degrees) {
    sum_sq += error_lsb * error_lsb;
    ++acc.samples;
    const double bin = std::fmin(std::ceil(error_lsb / kBinLsb), static_cast<double>(histogram.size() - 1));
    ++histogram[static_cast<size_t>(bin)];
    const bool interior = p.x >= kInteriorMarginPx && p.x <= 799.0 - kInteriorMarginPx &&
                          p.y >= kInteriorMarginPx && p.y <= 479.0 - kInteriorMarginPx;
    if (interior) acc.max_interior_lsb = std::fmax(acc.max_interior_lsb, error_lsb);
    if (error_lsb > acc.max_lsb) {
      acc.max_lsb = error_lsb;
      acc.worst_position = p;
      acc.worst_direction_deg = degrees;
    }
  };
  const bool directional = scene_.rendering() == Rendering::Directional;
  for (size_t i = 0; i < points_.size(); ++i) {
    const reference::DVec& p = points_[i];
    const Vec2 pf{static_cast<float>(p.x), static_cast<float>(p.y)};
    if (!directional) {
      const double a = static_cast<double>(plan.amplitude(pf, {}));
      record(std::fabs(a - value_[i]) / kLsb, p, 0.0);
      continue;
    }
    const reference::DVec g = field_[i];
    for (const Direction& dir : kDirs) {
      const double ref = max_g_ > 0.0
          ? std::fmin(1.0, std::fmax(0.0, 0.5 - (dir.d.x * g.x + dir.d.y * g.y) / (2.0 * max_g_)))
          : 0.5;
      const double a = static_cast<double>(plan.amplitude(pf, dir.f));
      record(std::fabs(a - ref) / kLsb, p, dir.degrees);
    }
  }
  acc.rms_lsb = acc.samples > 0 ? std::sqrt(sum_sq / static_cast<double>(acc.samples)) : 0.0;
  // Upper edge of the bin where 99 % of the samples are reached.
  const long wanted = static_cast<long>(std::ceil(0.99 * static_cast<double>(acc.samples)));
  long seen = 0;
  for (size_t b = 0; b < histogram.size(); ++b) {
    seen += histogram[b];
    if (seen >= wanted) {
      acc.p99_lsb = std::fmin(static_cast<double>(b) * kBinLsb, acc.max_lsb);
      break;
    }
  }
  return acc;
}

}  // namespace ff::bench
