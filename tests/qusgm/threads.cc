// Threads do not change QuSGM results: Pi and its gradient on a frictional
// pack with torsion and gravity (1728 grains, thousands of contacts, so
// the contact loop runs in many chunks and the scalar products in several
// blocks) are bit-identical with 1, 2 and 3 threads, and so are 300
// iterations of L-BFGS (displacements and rotations). The gradient itself
// is checked against finite differences in qusgm_contact_laws.
#include <deal.II/base/multithread_info.h>

#include <sable/base/common_parameters.h>
#include <sable/qusgm/minimizer.h>

#include <random>

#include "test_support.h"

using namespace sable::qusgm;
using sable_tests::check;

int
main()
{
  std::mt19937                           rng(11);
  std::uniform_real_distribution<double> uni(0, 1);
  const double                           r = 1e-4;
  const unsigned int                     side = 12;
  Pack                                   pack;
  // a jittered lattice with overlaps between neighbours
  for (unsigned int k = 0; k < side; ++k)
    for (unsigned int j = 0; j < side; ++j)
      for (unsigned int i = 0; i < side; ++i)
        pack.add_grain(Point<3>(1.9 * r * i + 0.05 * r * uni(rng),
                                1.9 * r * j + 0.05 * r * uni(rng),
                                1.9 * r * k + 0.05 * r * uni(rng)),
                       r * (0.9 + 0.2 * uni(rng)),
                       70e9 * (0.9 + 0.2 * uni(rng)),
                       0.2,
                       2420);
  Walls walls = bounding_walls(pack);
  for (unsigned int w = 0; w < 6; ++w)
    walls.position[w] += Walls::sign(w) * 0.02 * r;
  ContactModel model;
  model.friction      = 0.3;
  model.wall_friction = 0.3;
  model.torsion       = true;
  model.gravity       = true;
  ContactNetwork network;
  network.build(pack, walls, pack.centre, walls, model, 0.3 * pack.mean_radius());
  // random reference loads below the caps
  for (auto *contacts : {&network.pairs, &network.wall_contacts})
    for (Contact &c : *contacts)
      if (c.p0 > 0)
        {
          Tensor<1, 3> q;
          for (unsigned int d = 0; d < 3; ++d)
            q[d] = uni(rng) - 0.5;
          c.q0 = (0.8 * uni(rng) * c.q_max / q.norm()) * q;
          c.m0 = (uni(rng) - 0.5) * c.m_max;
        }
  network.update_reference(pack, walls, model);
  std::cout << pack.size() << " grains, " << network.pairs.size() << " pairs, "
            << network.wall_contacts.size() << " wall contacts" << std::endl;
  check("many chunks of contacts (128 per chunk)", network.pairs.size() > 10 * 128);

  const unsigned int n = pack.size();
  Vector<double>     theta(6 * n);
  for (unsigned int k = 0; k < 6 * n; ++k)
    theta[k] = 2e-3 * r * (uni(rng) - 0.5);
  Walls moved = walls;
  moved.position[2] += 0.01 * r;
  moved.position[5] -= 0.01 * r;

  double         pi_1 = 0;
  Vector<double> gradient_1, solution_1;
  unsigned int   iterations_1 = 0;
  for (const unsigned int threads : {1u, 2u, 3u})
    {
      sable::set_threads(threads);
      const std::string with = " with " + std::to_string(threads) + " threads";
      WorkFunctional    functional(pack, network, model);
      functional.set_walls(moved);
      Vector<double> gradient(6 * n);
      const double   pi = functional.value_and_gradient(theta, gradient);
      check("Pi by value() and value_and_gradient() the same" + with,
            functional.value(theta) == pi);

      // one increment on copies of the pack and network
      Pack              pack_copy    = pack;
      Walls             walls_copy   = walls;
      ContactNetwork    network_copy = network;
      MinimizerSettings settings;
      settings.method             = MinimizerSettings::Method::lbfgs;
      settings.sub_increments     = 1;
      settings.energy_tolerance   = 0;
      settings.gradient_tolerance = 0;
      settings.force_tolerance    = 1e-6;
      // a fixed budget: the random reference loads are far from
      // equilibrium, and what counts is that every iteration agrees
      settings.max_iterations = 300;
      IncrementSolver       solver(pack_copy, walls_copy, network_copy, model, settings);
      const IncrementResult result =
        solver.apply({{0, 0, 0.01 * r, 0, 0, -0.01 * r}});
      std::cout << "threads " << dealii::MultithreadInfo::n_threads() << ": Pi " << pi
                << ", " << result.iterations << " iterations" << std::endl;
      if (threads == 1)
        {
          pi_1         = pi;
          gradient_1   = gradient;
          solution_1   = solver.solution();
          iterations_1 = result.iterations;
          check("the increment runs its 300 iterations", result.iterations == 300);
          continue;
        }
      check("Pi bit-identical to one thread" + with, pi == pi_1);
      bool same = true;
      for (unsigned int k = 0; k < 6 * n; ++k)
        same = same && gradient[k] == gradient_1[k];
      check("gradient bit-identical to one thread" + with, same);
      same = result.iterations == iterations_1;
      for (unsigned int k = 0; k < 6 * n; ++k)
        same = same && solver.solution()[k] == solution_1[k];
      check("increment bit-identical to one thread" + with, same);
    }
  return sable_tests::exit_code();
}
