#include <deal.II/base/mpi.h>

#include <sable/base/input_error.h>
#include <sable/base/significant_digits.h>
#include <sable/qusgm/contact_laws.h>
#include <sable/qusgm/contact_network.h>

#include <boost/serialization/vector.hpp>

#include <algorithm>
#include <iterator>
#include <cmath>
#include <limits>

namespace sable::qusgm
{
  namespace
  {
    // Project a tangential reference load onto the plane normal to n,
    // keeping its magnitude, then cap it (the contact may have unloaded).
    Tensor<1, 3>
    project_and_cap(const Tensor<1, 3> &q,
                    const Tensor<1, 3> &n,
                    const double        cap)
    {
      const double magnitude = q.norm();
      if (magnitude == 0 || cap <= 0)
        return Tensor<1, 3>();
      const Tensor<1, 3> in_plane = q - (q * n) * n;
      const double       norm     = in_plane.norm();
      if (norm == 0)
        return Tensor<1, 3>();
      return (std::min(magnitude, cap) / norm) * in_plane;
    }
  } // namespace

  void
  ContactNetwork::initialise(Contact            &c,
                             const bool          wall,
                             const Pack         &pack,
                             const Walls        &walls,
                             const ContactModel &model) const
  {
    using namespace contact_laws;
    const unsigned int i = c.i;
    double             r_star, e_star, h0, k_s = 0, k_t = 0, lever_i, lever_j = 0;
    Tensor<1, 3>       n;
    const double       mu = wall ? model.wall_friction : model.friction;
    if (!wall)
      {
        const unsigned int j = c.other;
        const Tensor<1, 3> r = pack.centre[i] - pack.centre[j];
        const double       d = r.norm();
        n                    = r / d;
        h0     = pack.radius[i] + pack.radius[j] - d;
        r_star = effective_radius(pack.radius[i], pack.radius[j]);
        e_star = effective_modulus(pack.youngs_modulus[i],
                                   pack.poisson_ratio[i],
                                   pack.youngs_modulus[j],
                                   pack.poisson_ratio[j]);
        const double a0 = h0 > 0 ? std::sqrt(r_star * h0) : 0.;
        const double big_a =
          intersection_radius(pack.radius[i], pack.radius[j], d);
        lever_i = std::sqrt(std::max(0., std::pow(pack.radius[i], 2) - big_a * big_a));
        lever_j = std::sqrt(std::max(0., std::pow(pack.radius[j], 2) - big_a * big_a));
        if (mu > 0)
          k_s = shear_stiffness(a0,
                                pack.poisson_ratio[i],
                                pack.shear_modulus[i],
                                pack.poisson_ratio[j],
                                pack.shear_modulus[j]);
        if (mu > 0 && model.torsion)
          k_t = torsion_stiffness(a0,
                                  pack.shear_modulus[i],
                                  pack.shear_modulus[j]);
        c.h0 = h0;
        c.p0 = 0;
        c.k_n = hertz_coefficient(e_star, r_star);
        if (h0 > 0)
          c.p0 = hertz_force(c.k_n, h0);
        c.q_max = mu * c.p0;
        c.m_max = model.torsion ? torsion_cap(a0, mu, c.p0) : 0.;
      }
    else
      {
        const unsigned int w = c.other;
        n                    = Tensor<1, 3>();
        n[Walls::axis(w)]    = Walls::sign(w);
        h0     = walls.overlap(w, pack.centre[i], pack.radius[i]);
        r_star = pack.radius[i];
        e_star = effective_modulus(pack.youngs_modulus[i],
                                   pack.poisson_ratio[i],
                                   walls.youngs_modulus,
                                   walls.poisson_ratio);
        const double a0 = h0 > 0 ? std::sqrt(r_star * h0) : 0.;
        lever_i         = pack.radius[i] - std::max(h0, 0.);
        if (mu > 0)
          k_s = shear_stiffness(a0,
                                pack.poisson_ratio[i],
                                pack.shear_modulus[i],
                                walls.poisson_ratio,
                                walls.shear_modulus());
        if (mu > 0 && model.torsion)
          k_t = torsion_stiffness(a0, pack.shear_modulus[i], walls.shear_modulus());
        c.h0  = h0;
        c.k_n = hertz_coefficient(e_star, r_star);
        c.p0  = h0 > 0 ? hertz_force(c.k_n, h0) : 0.;
        c.q_max = mu * c.p0;
        c.m_max = model.torsion ? torsion_cap(a0, mu, c.p0) : 0.;
      }
    c.lever_i = lever_i;
    c.lever_j = lever_j;
    c.k_s     = c.p0 > 0 ? k_s : 0.;
    c.k_t     = c.p0 > 0 ? k_t : 0.;
    // Loads carried over from the last increment, rotated with the contact
    // plane and capped by the new Coulomb limits.
    c.q0 = (c.p0 > 0 && c.k_s > 0) ? project_and_cap(c.q0, n, c.q_max) :
                                     Tensor<1, 3>();
    c.m0 = (c.p0 > 0 && c.k_t > 0) ?
             std::max(-c.m_max, std::min(c.m_max, c.m0)) :
             0.;
  }

  void
  ContactNetwork::build(const Pack                  &pack,
                        const Walls                 &reference_walls,
                        const std::vector<Point<3>> &current,
                        const Walls                 &current_walls,
                        const ContactModel          &model,
                        const double                 skin_distance)
  {
    skin                 = skin_distance;
    const unsigned int n = pack.size();
    const double       cell_size = 2. * pack.max_radius() + skin;

    // Cell list over the bounding box of the grain centres, with at most
    // a few cells per grain (memory stays O(N) for any wall box).
    std::array<unsigned int, 3> n_cells;
    std::array<double, 3>       origin, extent;
    for (unsigned int a = 0; a < 3; ++a)
      {
        double lo = std::numeric_limits<double>::max(), hi = -lo;
        for (const Point<3> &x : current)
          {
            lo = std::min(lo, x[a]);
            hi = std::max(hi, x[a]);
          }
        origin[a] = lo;
        extent[a] = std::max(hi - lo, cell_size);
        n_cells[a] = std::max(1u, static_cast<unsigned int>(extent[a] / cell_size));
      }
    const double too_many = double(n_cells[0]) * n_cells[1] * n_cells[2] / (8. * n + 27.);
    if (too_many > 1)
      for (unsigned int a = 0; a < 3; ++a)
        n_cells[a] = std::max(1u, static_cast<unsigned int>(n_cells[a] / std::cbrt(too_many)));
    auto cell_index = [&](const Point<3> &x) {
      std::array<unsigned int, 3> c;
      for (unsigned int a = 0; a < 3; ++a)
        {
          const double s = (x[a] - origin[a]) / extent[a] * n_cells[a];
          c[a] = s <= 0 ? 0 :
                          std::min(n_cells[a] - 1, static_cast<unsigned int>(s));
        }
      return c;
    };
    const unsigned int total_cells = n_cells[0] * n_cells[1] * n_cells[2];
    std::vector<unsigned int> cell_start(total_cells + 1, 0), sorted(n),
      cell_of(n);
    for (unsigned int i = 0; i < n; ++i)
      {
        const auto c = cell_index(current[i]);
        cell_of[i]   = c[0] + n_cells[0] * (c[1] + n_cells[1] * c[2]);
        ++cell_start[cell_of[i] + 1];
      }
    for (unsigned int c = 0; c < total_cells; ++c)
      cell_start[c + 1] += cell_start[c];
    {
      std::vector<unsigned int> fill(cell_start.begin(), cell_start.end() - 1);
      for (unsigned int i = 0; i < n; ++i)
        sorted[fill[cell_of[i]]++] = i;
    }

    if (partition.n_grains() != n)
      partition = GrainPartition(pack, communicator);

    // The contacts of this rank's grains: a pair of two own grains once,
    // from its first grain; a pair with another rank's grain from ours.
    std::vector<Contact> new_pairs;
    new_pairs.reserve(pairs.size() + n);
    for (const unsigned int i : partition.owned_grains())
      {
        const auto c = cell_index(current[i]);
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
              {
                const int cx = int(c[0]) + dx, cy = int(c[1]) + dy,
                          cz = int(c[2]) + dz;
                if (cx < 0 || cy < 0 || cz < 0 || cx >= int(n_cells[0]) ||
                    cy >= int(n_cells[1]) || cz >= int(n_cells[2]))
                  continue;
                const unsigned int cell = cx + n_cells[0] * (cy + n_cells[1] * cz);
                for (unsigned int k = cell_start[cell]; k < cell_start[cell + 1];
                     ++k)
                  {
                    const unsigned int j = sorted[k];
                    if (j == i || (j < i && partition.is_owned(j)))
                      continue;
                    const double gap = (current[i] - current[j]).norm() -
                                       pack.radius[i] - pack.radius[j];
                    if (gap < skin)
                      {
                        Contact contact{};
                        contact.i     = std::min(i, j);
                        contact.other = std::max(i, j);
                        new_pairs.push_back(contact);
                      }
                  }
              }
      }
    const auto by_key = [n](const Contact &a, const Contact &b) {
      return a.key(n) < b.key(n);
    };
    std::sort(new_pairs.begin(), new_pairs.end(), by_key);

    std::vector<Contact> new_walls;
    for (const unsigned int i : partition.owned_grains())
      for (unsigned int w = 0; w < 6; ++w)
        if (current_walls.overlap(w, current[i], pack.radius[i]) > -skin)
          {
            Contact contact{};
            contact.i     = i;
            contact.other = w;
            new_walls.push_back(contact);
          }

    // Carry the reference state over by key (both lists are sorted).
    auto merge = [&](std::vector<Contact> &fresh, std::vector<Contact> &old) {
      std::size_t k = 0;
      for (Contact &c : fresh)
        {
          while (k < old.size() && old[k].key(n) < c.key(n))
            ++k;
          if (k < old.size() && old[k].key(n) == c.key(n))
            c = old[k];
          else
            c.p0 = -1; // marks a contact to initialise
        }
      old.swap(fresh);
    };
    merge(new_pairs, pairs);
    merge(new_walls, wall_contacts);
    for (Contact &c : pairs)
      if (c.p0 < 0)
        initialise(c, false, pack, reference_walls, model);
    for (Contact &c : wall_contacts)
      if (c.p0 < 0)
        initialise(c, true, pack, reference_walls, model);

    positions_at_build = current;
    walls_at_build     = current_walls;
    ++n_builds;
  }

  bool
  ContactNetwork::needs_rebuild(const std::vector<Point<3>> &current,
                                const Walls                 &current_walls,
                                const double                 extra_motion) const
  {
    if (positions_at_build.size() != current.size())
      return true;
    double max_grain = 0;
    for (unsigned int i = 0; i < current.size(); ++i)
      max_grain = std::max(max_grain,
                           (current[i] - positions_at_build[i]).norm_square());
    double max_wall = 0;
    for (unsigned int w = 0; w < 6; ++w)
      max_wall = std::max(max_wall,
                          std::abs(current_walls.position[w] -
                                   walls_at_build.position[w]));
    // Two grains approaching each other both count.
    return 2. * std::sqrt(max_grain) + max_wall + extra_motion > 0.5 * skin;
  }

  void
  ContactNetwork::update_reference(const Pack         &pack,
                                   const Walls        &walls,
                                   const ContactModel &model)
  {
    for (Contact &c : pairs)
      initialise(c, false, pack, walls, model);
    for (Contact &c : wall_contacts)
      initialise(c, true, pack, walls, model);
  }

  void
  ContactNetwork::set_reference_loads(const Pack                     &pack,
                                      const Walls                    &walls,
                                      const ContactModel             &model,
                                      const double                    skin_distance,
                                      const std::vector<ContactLoad> &loads)
  {
    if (positions_at_build.size() != pack.size())
      build(pack, walls, pack.centre, walls, model, skin_distance);
    const unsigned int n = pack.size();
    for (const ContactLoad &load : loads)
      {
        // Closed at the reference? (every rank decides alike)
        const double h =
          load.wall ? walls.overlap(load.other, pack.centre[load.i], pack.radius[load.i]) :
                      pack.radius[load.i] + pack.radius[load.other] -
                        (pack.centre[load.i] - pack.centre[load.other]).norm();
        if (!(h > 0))
          check_input(false,
                      load.where,
                      pack.name(load.i) + " and " +
                        (load.wall ? std::string("wall ") + Walls::name(load.other) :
                                     pack.name(load.other)) +
                        ", overlap " + significant_digits(h) + " m",
                      "contacts whose grains overlap (a closed contact of the pack)");
        std::vector<Contact> &list = load.wall ? wall_contacts : pairs;
        Contact               probe{};
        probe.i     = load.i;
        probe.other = load.other;
        const auto found =
          std::lower_bound(list.begin(), list.end(), probe, [n](const Contact &a, const Contact &b) {
            return a.key(n) < b.key(n);
          });
        if (found == list.end() || found->key(n) != probe.key(n))
          continue; // held by another rank
        Contact     &c = *found;
        Tensor<1, 3> normal;
        if (load.wall)
          normal[Walls::axis(c.other)] = Walls::sign(c.other);
        else
          normal = (pack.centre[c.i] - pack.centre[c.other]) /
                   (pack.centre[c.i] - pack.centre[c.other]).norm();
        const Tensor<1, 3> &q = load.tangential_force;
        const double        m = load.torsional_couple;
        if (c.p0 > 0 && c.k_s > 0)
          {
            const bool as_given = std::abs(q * normal) <= 1e-9 * q.norm() &&
                                  q.norm() <= c.q_max * (1 + 1e-12);
            c.q0 = as_given ? q : project_and_cap(q, normal, c.q_max);
          }
        else
          c.q0 = Tensor<1, 3>();
        c.m0 = (c.p0 > 0 && c.k_t > 0) ?
                 (std::abs(m) <= c.m_max * (1 + 1e-12) ?
                    m :
                    std::max(-c.m_max, std::min(c.m_max, m))) :
                 0.;
      }
  }

  std::vector<Contact>
  ContactNetwork::gather_on_root(const std::vector<Contact> &held,
                                 const unsigned int          n_grains) const
  {
    std::vector<Contact> own;
    std::copy_if(held.begin(), held.end(), std::back_inserter(own), [&](const Contact &c) {
      return owns(c);
    });
    if (partition.n_ranks() <= 1)
      return own;
    std::vector<Contact> all;
    for (const auto &part : dealii::Utilities::MPI::gather(partition.get_communicator(), own, 0))
      all.insert(all.end(), part.begin(), part.end());
    std::sort(all.begin(), all.end(), [n_grains](const Contact &a, const Contact &b) {
      return a.key(n_grains) < b.key(n_grains);
    });
    return all;
  }
} // namespace sable::qusgm
