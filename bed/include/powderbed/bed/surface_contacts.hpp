#pragma once
// Where a sphere touches a HeightMap's surface of triangles: at each local minimum of the
// distance from its centre to the surface that lies within its radius. A sphere in a valley
// touches both slopes, one on a ridge touches the ridge once, one over a plane the plane once.
// One contact at the nearest point only (what the spread had) holds a sphere between two slopes
// by the nearer one alone, and it rocks there for ever (docs/build.md "Limits"); LIGGGHTS's
// mesh walls likewise keep one contact per touched triangle and drop the duplicates at shared
// edges and corners. A point on an edge or corner is a local minimum when every triangle that
// holds it finds it nearest; a face point always is.
#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "powderbed/bed/height_map.hpp"

namespace powderbed::bed {

// A sphere touches at most this many facets: four slopes meeting in a pit (more are dropped,
// the shallowest first).
constexpr std::size_t kMaxSurfaceContacts = 4;

struct SurfaceContact {
  std::size_t facet;    // a triangle that holds the point (HeightMap::triangle), the lowest index
  double offset[3];     // from the centre (x, y clamped onto the grid) to the point, m
  double distance;      // |offset| < r, m
};

// The contacts of a sphere at (x, y, zc) of radius r whose centre lies above the surface under
// it, deepest first (ties by facet); how many.
std::size_t surface_contacts(const HeightMap& surface, double x, double y, double zc, double r,
                             std::array<SurfaceContact, kMaxSurfaceContacts>& out);

// A triangle of the surface and the image of it a sphere meets: moved by whole cells (a period's
// worth along a periodic axis; 0 on the grid itself).
struct TriangleImage {
  std::size_t triangle;
  std::array<std::ptrdiff_t, 2> cells;
};

// The triangles within `reach` (> r) of a sphere's centre, appended to `near`: a list the
// spread finds once per prune of its neighbour list and reads every step until the next, as
// LIGGGHTS keeps a neighbour list of mesh triangles per particle.
void triangles_near(const HeightMap& surface, double x, double y, double zc, double reach,
                    std::vector<TriangleImage>& near);

// surface_contacts among `near` only, found by triangles_near from a centre this one lies within
// reach - r of, each image moved on by `wrapped` cells (the whole periods the centre was wrapped
// by since): the same contacts as the search of the whole surface.
std::size_t surface_contacts(const HeightMap& surface, double x, double y, double zc, double r,
                             std::span<const TriangleImage> near, std::array<std::ptrdiff_t, 2> wrapped,
                             std::array<SurfaceContact, kMaxSurfaceContacts>& out);

// How deep a sphere reaches into the surface: r less its distance to the nearest point (its
// deepest contact), or r plus the depth of its centre when that lies at or below the surface
// under it; 0 when it touches nothing (fusion's capture, thermal/fusion.cpp).
double surface_overlap(const HeightMap& surface, double x, double y, double zc, double r);

}  // namespace powderbed::bed
