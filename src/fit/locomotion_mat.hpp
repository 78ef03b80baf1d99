#pragma once
// One trial of the "Stick Insect Locomotion" database (Theunissen, Bekemeier & Duerr 2015;
// docs/recordings.md): a MATLAB file (v5, or v7.3 through HDF5), read with matio.
//  - frame rate experiment.FREQUENCY(1) (Hz) and experiment.N_FRAMES;
//  - per leg L1 L2 L3 R1 R2 R3: <leg>.cox.angle (N x 3 deg, rotations in the order
//    <leg>.cox.ROTSEQ; the z rotation is the ThC joint's protraction/retraction), <leg>.fem.angle
//    (N, CTr) and <leg>.tib.angle (N, FTi), as channels <leg>.thc, <leg>.ctr, <leg>.fti in the
//    lab's angle conventions (a fit maps them to the model's through observables);
//  - contact.<leg>.time: one row per stance, [touchdown, lift-off] frame (1-based). A
//    touchdown at the first frame or a lift-off at the last is the recording's edge, not an
//    event, and is stored as NaN. A touchdown (lift-off) frame is the first frame in (out of)
//    contact, so the event lies after the frame before it: its time is taken halfway between.
// Every structural surprise (no such variable or field, a wrong shape or class, contact
// frames out of range or out of order, a channel without a finite sample) throws Error
// "<file>: <field>: ..." in one line; nothing is guessed.
#include <string>
#include <vector>

#include "fit/kinematic_data.hpp"

namespace phasmid::fit {

// The legs of the database, in its order.
const std::vector<std::string>& locomotion_legs();

// `legs` empty: all six legs. Time 0 is the first frame.
KinematicData read_locomotion_mat(const std::string& path, const std::vector<std::string>& legs = {});

}  // namespace phasmid::fit
