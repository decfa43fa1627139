/* spacetree-dem: run-time checks of pair_style trimesh against the rest of the deck, made at
   each init: combinations that would otherwise run without error and without the contacts the
   user asked for. */

#ifndef LMP_TRIMESH_DECK_CHECKS_H
#define LMP_TRIMESH_DECK_CHECKS_H

namespace LAMMPS_NS {

class FixTrimeshTemplate;
class LAMMPS;

// Every pair of template types (not both obstacles) must reach pair_style trimesh. Under
// pair_style hybrid or hybrid/overlay a type pair without `pair_coeff I J trimesh` gets no
// trimesh list: its grains pass through each other, or meet as another style's spheres.
void check_template_types_reach_trimesh(LAMMPS *lmp, const FixTrimeshTemplate &templ);

// Every movable grain (bounding radius + eps, as the neighbour lists see it) must fit in the
// box, whatever the neighbour style: wider than a fixed box (boundary f) it cannot be inside
// it; with the skin wider than a periodic box it meets its own image. (Obstacles may be
// larger; shrink-wrapped boundaries follow the atoms.)
void check_grains_fit_box(LAMMPS *lmp, const FixTrimeshTemplate &templ);

}  // namespace LAMMPS_NS

#endif
