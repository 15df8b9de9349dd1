// SPDX-License-Identifier: GPL-3.0-or-later
// Private: the mesher's last stage: closed components of the mesh face outward. Never
// installed.
#pragma once

#include "reconstruction/mesh_state.h"

namespace pcl {
namespace cocone {
namespace detail {

/** Flips every closed component of the mesh of \a mesh whose signed volume is
 * negative (see the source). Needs one fan per vertex, and every boundary edge among
 * the edges noted as maybe open. */
void orientClosedComponentsOutward(MeshState& mesh);

} // namespace detail
} // namespace cocone
} // namespace pcl
