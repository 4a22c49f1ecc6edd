// What the machine generators share: a Scene with an empty World and its
// CableSystem, and the bodies every machine is made of (common.cpp).
#pragma once

#include <memory>
#include <string>

#include "reeve/machines/machines.h"

namespace reeve::machines::detail {

/// An empty scene named `name`, gravity `g` m/s^2 along -y, the budget's
/// substeps and iterations, frames at 60 Hz.
Scene emptyScene(const std::string& name, double g, const Budget& budget);

/// A dynamic wheel: a solid cylinder of radius `r` (m), 0.1 m thick along
/// local z, of `mass` (kg), turned so that local z is `axis`.
BodyId addWheel(World& world, const std::string& name, double r, double mass, const Vec3& at,
                const Vec3& axis = Vec3::UnitZ());

/// A dynamic box with half extents `half` (m) and `mass` (kg).
BodyId addBox(World& world, const std::string& name, const Vec3& half, double mass, const Vec3& at);

}  // namespace reeve::machines::detail
