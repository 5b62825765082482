#ifndef sable_mpm_particle_layout_h
#define sable_mpm_particle_layout_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <cmath>

namespace sable::mpm
{
  /**
   * Where each quantity sits in a particle's property array. Offsets are
   * fixed once the bodies (and so the materials) are known; history slots
   * exist only if some body's material needs them, the initial position
   * only if the displacement is written (Output/Displacement output).
   *
   *   mass | initial volume | body | velocity (dim) | F (dim x dim, row-major)
   *   | stress (xx yy zz xy xz yz) | history (n_history)
   *   | initial position (dim, if stored)
   *   | velocity gradient C of the affine transfers (dim x dim, row-major,
   *     if stored)
   *   | outward unit normal N of the body's face nearest the point in the
   *     reference configuration (dim, zero deeper inside, if stored)
   *   | the vector from the point to its body's surface in the reference
   *     configuration (dim, zero deeper inside, if stored)
   */
  template <int dim>
  struct ParticleLayout
  {
    static constexpr unsigned int mass           = 0;
    static constexpr unsigned int initial_volume = 1;
    static constexpr unsigned int body           = 2;
    static constexpr unsigned int velocity       = 3;
    static constexpr unsigned int deformation    = velocity + dim;
    static constexpr unsigned int stress         = deformation + dim * dim;
    static constexpr unsigned int history        = stress + 6;

    unsigned int n_history = 0;

    /// Whether each point keeps the position it was seeded at.
    bool initial_position_stored = false;

    /// Whether each point carries the velocity gradient C of the affine
    /// transfers (Solver/Affine transfers).
    bool affine_stored = false;

    /// Whether each point carries its body's reference surface normal
    /// (the contact's `flatter body` normals).
    bool surface_normal_stored = false;

    /// Whether each point carries the vector to its body's face (with the
    /// surface normal, for the contact's surface positions).
    bool to_surface_stored = false;

    /// Offset of the initial position (if stored).
    unsigned int
    initial_position() const
    {
      return history + n_history;
    }

    /// Offset of the affine velocity gradient C (if stored).
    unsigned int
    affine() const
    {
      return initial_position() + (initial_position_stored ? dim : 0);
    }

    /// Offset of the reference surface normal (if stored).
    unsigned int
    surface_normal() const
    {
      return affine() + (affine_stored ? dim * dim : 0);
    }

    unsigned int
    n_properties() const
    {
      return to_surface() + (to_surface_stored ? dim : 0);
    }

    /// Offset of the vector to the surface (if stored).
    unsigned int
    to_surface() const
    {
      return surface_normal() + (surface_normal_stored ? dim : 0);
    }

    /// The point's vector to its body's surface in the reference
    /// configuration (zero where it carries none), if the layout stores it.
    template <typename Properties>
    dealii::Tensor<1, dim>
    reference_to_surface(const Properties &props) const
    {
      return vector_at(props, to_surface());
    }

    /// The point's reference surface normal N (zero where it carries none),
    /// if the layout stores it.
    template <typename Properties>
    dealii::Tensor<1, dim>
    reference_surface_normal(const Properties &props) const
    {
      return vector_at(props, surface_normal());
    }

    /// The dim properties from @p offset on, as a vector.
    template <typename Properties>
    static dealii::Tensor<1, dim>
    vector_at(const Properties &props, const unsigned int offset)
    {
      dealii::Tensor<1, dim> v;
      for (unsigned int d = 0; d < dim; ++d)
        v[d] = props[offset + d];
      return v;
    }

    /// Index among the stress components (xx yy zz xy xz yz) of (i, j).
    static constexpr unsigned int
    stress_component(const unsigned int i, const unsigned int j)
    {
      return i == j ? i : (i + j == 1 ? 3u : (i + j == 2 ? 4u : 5u));
    }

    template <typename Properties>
    static dealii::Tensor<2, dim>
    deformation_gradient(const Properties &props)
    {
      dealii::Tensor<2, dim> F;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          F[i][j] = props[deformation + i * dim + j];
      return F;
    }

    /// Store @p C as the point's affine velocity gradient.
    template <typename Properties>
    void
    set_affine(Properties &props, const dealii::Tensor<2, dim> &C) const
    {
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          props[affine() + i * dim + j] = C[i][j];
    }

    /// The point's affine velocity gradient C (if stored).
    template <typename Properties>
    dealii::Tensor<2, dim>
    affine_gradient(const Properties &props) const
    {
      dealii::Tensor<2, dim> C;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          C[i][j] = props[affine() + i * dim + j];
      return C;
    }

    /// The full (3 x 3) Cauchy stress.
    template <typename Properties>
    static dealii::SymmetricTensor<2, 3>
    stress_tensor(const Properties &props)
    {
      dealii::SymmetricTensor<2, 3> sigma;
      for (unsigned int c = 0; c < 6; ++c)
        sigma.access_raw_entry(c) = props[stress + c];
      return sigma;
    }

    /// V sigma restricted to the dim x dim plane, V = det(F) V0: the
    /// particle's share in the internal nodal forces -V sigma . grad N.
    template <typename Properties>
    static dealii::Tensor<2, dim>
    volume_stress(const Properties &props)
    {
      const double volume =
        dealii::determinant(deformation_gradient(props)) * props[initial_volume];
      dealii::Tensor<2, dim> result;
      for (unsigned int i = 0; i < dim; ++i)
        for (unsigned int j = 0; j < dim; ++j)
          result[i][j] = volume * props[stress + stress_component(i, j)];
      return result;
    }

    /// The spacing the point was seeded at, V0^(1/dim): on an adapted grid
    /// a cell may hold points seeded on a coarser or finer one.
    template <typename Properties>
    static double
    seeding_spacing(const Properties &props)
    {
      return spacing_of_volume(props[initial_volume]);
    }

    /// The seeding spacing of a point of initial volume @p volume.
    static double
    spacing_of_volume(const double volume)
    {
      return dim == 2 ? std::sqrt(volume) : std::cbrt(volume);
    }
  };
} // namespace sable::mpm

#endif
