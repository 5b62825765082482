// Which MPI rank owns which grain of a QuSGM pack.
#ifndef sable_qusgm_grain_partition_h
#define sable_qusgm_grain_partition_h

#include <deal.II/base/mpi.h>

#include <sable/qusgm/pack.h>

#include <vector>

namespace sable::qusgm
{
  /**
   * Grains distributed over the ranks by space: the pack's Morton order
   * (Pack::spatial_order()) cut into one segment of equal length per
   * rank, fixed for the run. A rank evaluates the contacts of the grains
   * it owns and gathers their forces; a contact between grains of two ranks
   * is evaluated on both, with identical inputs, so that no rank waits for
   * another's contact forces.
   *
   * The pack (centres, radii, moduli) and the unknowns are replicated on
   * every rank, and every rank sums per-grain contributions in grain order
   * after gather(). So results are the same, bit for bit, on any number of
   * ranks; the price is O(N) memory per rank and an all-gather of a few
   * numbers per grain at each evaluation.
   */
  class GrainPartition
  {
  public:
    /// No grains yet.
    GrainPartition() = default;

    GrainPartition(const Pack &pack, MPI_Comm communicator);

    unsigned int
    n_grains() const
    {
      return owner.size();
    }

    bool
    is_owned(const unsigned int grain) const
    {
      return owner[grain] == rank;
    }

    /// The grains this rank owns, ascending (all grains on one rank).
    const std::vector<unsigned int> &
    owned_grains() const
    {
      return owned;
    }

    unsigned int
    n_ranks() const
    {
      return size;
    }

    MPI_Comm
    get_communicator() const
    {
      return communicator;
    }

    /**
     * Give every rank the owners' values: @p values holds @p components
     * numbers per grain; the entries of owned grains are sent, the others
     * are overwritten.
     */
    void
    gather(std::vector<double> &values, unsigned int components) const;

    /// Sum over the ranks (one rank: @p value).
    double
    sum(double value) const;

    double
    max(double value) const;

    /// Sum of per-grain counts that each rank set for its own grains.
    void
    sum(std::vector<unsigned int> &counts) const;

  private:
    MPI_Comm                  communicator = MPI_COMM_SELF;
    unsigned int              rank = 0, size = 1;
    std::vector<unsigned int> owner;
    std::vector<unsigned int> owned;
    /// all ranks' grains in rank order, and where each rank's part starts
    std::vector<unsigned int> grains_by_rank;
    std::vector<int>          rank_start;
    mutable std::vector<double> send_buffer, receive_buffer;
  };
} // namespace sable::qusgm

#endif
