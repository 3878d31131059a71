// The size rules of an advancing front that do not depend on its dimension: how large an
// element an item (a face of the volume front, a side of the surface front) forms for the size
// wanted there, and where the item waits in the queue (steps F5, F6, F9 / S1, S9). The size
// wanted itself is eq. 15 (core/sizing/attached_sizes.h: new_point_size over the item's
// corners, with the SizeField read near the item).
#pragma once

#include <algorithm>

namespace afmesh {

// Not in the paper: an item's element is kept within these multiples of the item's mean edge,
// so that it is neither needle- nor flat-shaped whatever size is wanted; a front much coarser
// or finer than the size wanted grades towards it over a few layers instead.
inline constexpr double kMinElementOverEdge = 0.55;
inline constexpr double kMaxElementOverEdge = 1.6;

// F5/F9: the size of the element an item of mean edge `mean_edge` forms for the wanted size
// `target`: target clamped to [kMinElementOverEdge, kMaxElementOverEdge] × mean_edge.
inline double element_size_for_target(double target, double mean_edge) {
  return std::clamp(target, kMinElementOverEdge * mean_edge, kMaxElementOverEdge * mean_edge);
}

// F6/S1: the queue key of an item whose element size is d (element_size_for_target) for the
// wanted size `target`: d, except for an item whose element is clamped above the target (an
// item of an input much coarser than the size wanted inside), whose key is target² / d, below
// the target. Ordered by its element size, such an item would wait until every item of the
// target size was deleted: the front grown from those would sweep the domain and leave the
// coarse boundary items for the end, in thin gaps along the boundary where only ever smaller
// elements fit (the volume front got stuck there). Queued first, the coarse items form the
// layer that takes the front from the boundary's size down to the target, as the first layer
// does on a matching boundary.
inline double queue_key_for_element(double target, double d) {
  return d <= target ? d : target * target / d;
}

}  // namespace afmesh
