// A pack of elastic spheres (structure of arrays) and its six walls.
#ifndef sable_qusgm_pack_h
#define sable_qusgm_pack_h

#include <deal.II/base/point.h>

#include <boost/serialization/version.hpp>

#include <array>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

namespace sable::qusgm
{
  using dealii::Point;
  using dealii::Tensor;

  /**
   * Grain data as one array per quantity. `centre` is the reference
   * configuration: the last equilibrium reached. `id` is the grain's name
   * in the files it came from and goes to (the `id` column of a pack file,
   * a LAMMPS atom id; else its position in the file, from 0): output that
   * names grains uses it.
   */
  struct Pack
  {
    std::vector<Point<3>>      centre;
    std::vector<double>        radius;
    std::vector<double>        youngs_modulus;
    std::vector<double>        poisson_ratio;
    std::vector<double>        shear_modulus;
    std::vector<double>        density;
    std::vector<std::uint64_t> id;

    template <class Archive>
    void
    serialize(Archive &ar, const unsigned int version)
    {
      ar &centre &radius &youngs_modulus &poisson_ratio &shear_modulus &density;
      if (version >= 1)
        ar &id;
      else
        {
          id.resize(centre.size());
          std::iota(id.begin(), id.end(), std::uint64_t(0));
        }
    }

    unsigned int
    size() const
    {
      return centre.size();
    }

    /// Add a grain; its id is @p grain_id, or its index if none is given.
    void
    add_grain(const Point<3> &x,
              double          r,
              double          e,
              double          nu,
              double          rho,
              std::uint64_t   grain_id = std::uint64_t(-1));

    /// "grain 12" or, when the id differs from the index, "grain 12 (id 57)".
    std::string
    name(unsigned int i) const;

    double
    mass(const unsigned int i) const;

    double
    mean_radius() const;

    double
    max_radius() const;

    double
    mean_youngs_modulus() const;

    /// Reorder the grains: new grain k is old grain permutation[k].
    void
    permute(const std::vector<unsigned int> &permutation);

    /**
     * Renumber the grains along a Morton (Z-order) curve of cells of about
     * one diameter, so that neighbours in space are close in memory.
     */
    void
    sort_spatially();

    /// The order of sort_spatially(): position k holds the grain that
    /// comes k-th along the Morton curve.
    std::vector<unsigned int>
    spatial_order() const;

    /**
     * Throw InputError (naming @p source) unless the pack has at least two
     * grains, each with a finite centre, radius > 0, E > 0,
     * -1 < nu < 0.5 and density > 0, and the ids are distinct.
     */
    void
    check(const std::string &source) const;
  };

  /**
   * Six planar elastic walls aligned with the axes. Wall w < 3 is the lower
   * wall of axis w (inward normal +e_w), wall w >= 3 the upper wall of axis
   * w - 3 (inward normal -e_{w-3}).
   */
  struct Walls
  {
    std::array<double, 6> position{{0, 0, 0, 1, 1, 1}};
    double                youngs_modulus = 7e12;
    double                poisson_ratio  = 0.495;

    template <class Archive>
    void
    serialize(Archive &ar, const unsigned int)
    {
      for (double &x : position)
        ar &x;
      ar &youngs_modulus &poisson_ratio;
    }

    static unsigned int
    axis(const unsigned int w)
    {
      return w % 3;
    }

    /// +1 for a lower wall, -1 for an upper wall.
    static double
    sign(const unsigned int w)
    {
      return w < 3 ? 1. : -1.;
    }

    double
    shear_modulus() const
    {
      return youngs_modulus / (2. * (1. + poisson_ratio));
    }

    double
    length(const unsigned int a) const
    {
      return position[a + 3] - position[a];
    }

    double
    area(const unsigned int a) const
    {
      return length((a + 1) % 3) * length((a + 2) % 3);
    }

    double
    volume() const
    {
      return length(0) * length(1) * length(2);
    }

    Point<3>
    centre() const;

    /// Overlap of a sphere with wall w: R - (x - x_w).n_w.
    double
    overlap(const unsigned int w, const Point<3> &x, const double r) const
    {
      return r - sign(w) * (x[axis(w)] - position[w]);
    }

    /// Throw InputError unless the walls enclose a box of positive size.
    void
    check() const;

    /// "x_min", "y_min", "z_min", "x_max", "y_max", "z_max" for w = 0..5.
    static const char *
    name(unsigned int w);
  };

  /**
   * Throw InputError (naming @p source and the grains) if two grains
   * coincide, or a grain overlaps another grain by more than
   * @p max_overlap times the smaller radius, or a wall by more than
   * @p max_overlap times its radius. A cell list: O(N).
   */
  void
  check_overlaps(const Pack        &pack,
                 const Walls       &walls,
                 double             max_overlap,
                 const std::string &source);

  /// The tightest box of walls around the pack (grains just touching).
  Walls
  bounding_walls(const Pack &pack);
} // namespace sable::qusgm

// Version 1 added the grain ids (version 0: ids are the indices).
BOOST_CLASS_VERSION(sable::qusgm::Pack, 1)

#endif
