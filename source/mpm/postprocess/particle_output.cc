#include <sable/mpm/postprocess/particle_output.h>

#include <cmath>

namespace sable::mpm
{
  namespace
  {
    constexpr const char *axes = "xyz";

    /// Row-major component names of a 3 x 3 tensor: name_xx, name_xy, ...
    void
    add_tensor_names(std::vector<std::string> &names, const std::string &name)
    {
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          names.push_back(name + "_" + axes[i] + axes[j]);
    }

    /// sigma_1 - sigma_2 of the stress's x-y block
    double
    in_plane_difference(const SymmetricTensor<2, 3> &s)
    {
      return std::sqrt((s[0][0] - s[1][1]) * (s[0][0] - s[1][1]) + 4 * s[0][1] * s[0][1]);
    }
  } // namespace

  template <int dim>
  ParticleOutput<dim>::ParticleOutput(const ParticleLayout<dim> &     layout,
                                      const std::vector<std::string> &history_names,
                                      const bool                      tensors,
                                      const bool                      smoothed)
    : layout(layout)
    , smoothed(smoothed)
  {
    using Interpretation = DataComponentInterpretation::DataComponentInterpretation;
    names                = {"id", "body", "mass", "initial_volume"};
    const auto add_range = [&](const unsigned int first, const std::string &name,
                               const Interpretation kind) {
      ranges.emplace_back(first, names.size() - 1, name, kind);
    };

    velocity = names.size();
    for (unsigned int d = 0; d < dim; ++d)
      names.push_back("velocity");
    add_range(velocity, "velocity", DataComponentInterpretation::component_is_part_of_vector);

    displacement = names.size();
    if (layout.initial_position_stored)
      {
        for (unsigned int d = 0; d < dim; ++d)
          names.push_back("displacement");
        add_range(displacement,
                  "displacement",
                  DataComponentInterpretation::component_is_part_of_vector);
      }

    deformation = names.size();
    add_tensor_names(names, "F");
    if (tensors)
      add_range(deformation, "F", DataComponentInterpretation::component_is_part_of_tensor);
    stress = names.size();
    add_tensor_names(names, "stress");
    if (tensors)
      add_range(stress, "stress", DataComponentInterpretation::component_is_part_of_tensor);

    names.push_back("pressure");
    names.push_back("von_mises");
    for (unsigned int h = 0; h < layout.n_history; ++h)
      names.push_back(h < history_names.size() ? history_names[h] : "history_" + std::to_string(h));
    smoothed_stress = names.size();
    if (smoothed)
      {
        add_tensor_names(names, "smoothed_stress");
        if (tensors)
          add_range(smoothed_stress,
                    "smoothed_stress",
                    DataComponentInterpretation::component_is_part_of_tensor);
        names.push_back("smoothed_pressure");
        names.push_back("smoothed_von_mises");
        names.push_back("smoothed_stress_difference");
      }
  }

  template <int dim>
  void
  ParticleOutput<dim>::build_patches(const Particles::ParticleHandler<dim> &particles,
                                     const StressSmoothing<dim> *            smoothing)
  {
    Assert(!smoothed || smoothing != nullptr, ExcMessage("The smoothed stress is missing."));
    using Layout = ParticleLayout<dim>;
    patches.resize(particles.n_locally_owned_particles());
    unsigned int i = 0;
    for (const auto &particle : particles)
      {
        DataOutBase::Patch<0, dim> &patch = patches[i];
        patch.vertices[0]                 = particle.get_location();
        patch.patch_index                 = i++;
        patch.data.reinit(names.size(), 1);
        const auto props = particle.get_properties();
        const auto value = [&](const unsigned int c) -> float & { return patch.data(c, 0); };

        value(0) = particle.get_id();
        value(1) = props[Layout::body];
        value(2) = props[Layout::mass];
        value(3) = props[Layout::initial_volume];
        for (unsigned int d = 0; d < dim; ++d)
          value(velocity + d) = props[Layout::velocity + d];
        if (layout.initial_position_stored)
          for (unsigned int d = 0; d < dim; ++d)
            value(displacement + d) =
              particle.get_location()[d] - props[layout.initial_position() + d];

        // F and stress as 3 x 3: in 2D (plane strain) F_zz = 1 and
        // F_xz = F_zx = ... = 0, while stress_zz is the material's
        const Tensor<2, dim> F = Layout::deformation_gradient(props);
        for (unsigned int r = 0; r < 3; ++r)
          for (unsigned int c = 0; c < 3; ++c)
            value(deformation + 3 * r + c) = (r < dim && c < dim) ? F[r][c] : (r == c ? 1. : 0.);
        const SymmetricTensor<2, 3> sigma = Layout::stress_tensor(props);
        for (unsigned int r = 0; r < 3; ++r)
          for (unsigned int c = 0; c < 3; ++c)
            value(stress + 3 * r + c) = sigma[r][c];

        const SymmetricTensor<2, 3> s = deviator(sigma);
        value(stress + 9)             = -trace(sigma) / 3.;
        value(stress + 10)            = std::sqrt(1.5 * scalar_product(s, s));
        for (unsigned int h = 0; h < layout.n_history; ++h)
          value(stress + 11 + h) = props[Layout::history + h];
        if (smoothed)
          {
            const SymmetricTensor<2, 3> &smooth = (*smoothing)[particle.get_local_index()];
            for (unsigned int r = 0; r < 3; ++r)
              for (unsigned int c = 0; c < 3; ++c)
                value(smoothed_stress + 3 * r + c) = smooth[r][c];
            const SymmetricTensor<2, 3> s = deviator(smooth);
            value(smoothed_stress + 9)    = -trace(smooth) / 3.;
            value(smoothed_stress + 10)   = std::sqrt(1.5 * scalar_product(s, s));
            value(smoothed_stress + 11)   = in_plane_difference(smooth);
          }
      }
  }

  template class ParticleOutput<2>;
  template class ParticleOutput<3>;
} // namespace sable::mpm
