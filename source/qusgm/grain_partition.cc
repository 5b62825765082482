#include <sable/qusgm/grain_partition.h>

#include <algorithm>
#include <cstdint>

namespace sable::qusgm
{
  GrainPartition::GrainPartition(const Pack &pack, const MPI_Comm communicator)
    : communicator(communicator)
    // (programs that embed QuSGM need not initialise MPI)
    , rank(dealii::Utilities::MPI::job_supports_mpi() ?
             dealii::Utilities::MPI::this_mpi_process(communicator) :
             0)
    , size(dealii::Utilities::MPI::job_supports_mpi() ?
             dealii::Utilities::MPI::n_mpi_processes(communicator) :
             1)
    , owner(pack.size(), 0)
    , rank_start(size + 1, 0)
  {
    const unsigned int n = pack.size();
    // Equal segments of the Morton curve: compact regions with equal
    // numbers of grains (and so, in a pack, about equal numbers of
    // contacts). Every rank computes the same cut from the same pack.
    const std::vector<unsigned int> order =
      size > 1 ? pack.spatial_order() : std::vector<unsigned int>();
    for (unsigned int r = 0; r < size; ++r)
      {
        const unsigned int begin = (std::uint64_t(n) * r) / size;
        const unsigned int end   = (std::uint64_t(n) * (r + 1)) / size;
        for (unsigned int k = begin; k < end && size > 1; ++k)
          owner[order[k]] = r;
      }
    grains_by_rank.reserve(n);
    for (unsigned int r = 0; r < size; ++r)
      {
        rank_start[r] = grains_by_rank.size();
        for (unsigned int i = 0; i < n; ++i)
          if (owner[i] == r)
            grains_by_rank.push_back(i);
      }
    rank_start[size] = grains_by_rank.size();
    owned.assign(grains_by_rank.begin() + rank_start[rank],
                 grains_by_rank.begin() + rank_start[rank + 1]);
  }

  void
  GrainPartition::gather(std::vector<double> &values, const unsigned int components) const
  {
    if (size == 1)
      return;
    send_buffer.resize(owned.size() * components);
    for (std::size_t k = 0; k < owned.size(); ++k)
      std::copy_n(&values[std::size_t(owned[k]) * components],
                  components,
                  &send_buffer[k * components]);
    std::vector<int> counts(size), displacements(size);
    for (unsigned int r = 0; r < size; ++r)
      {
        counts[r]        = (rank_start[r + 1] - rank_start[r]) * components;
        displacements[r] = rank_start[r] * components;
      }
    receive_buffer.resize(grains_by_rank.size() * components);
    const int ierr = MPI_Allgatherv(send_buffer.data(),
                                    send_buffer.size(),
                                    MPI_DOUBLE,
                                    receive_buffer.data(),
                                    counts.data(),
                                    displacements.data(),
                                    MPI_DOUBLE,
                                    communicator);
    AssertThrowMPI(ierr);
    for (std::size_t k = 0; k < grains_by_rank.size(); ++k)
      std::copy_n(&receive_buffer[k * components],
                  components,
                  &values[std::size_t(grains_by_rank[k]) * components]);
  }

  double
  GrainPartition::sum(const double value) const
  {
    return size == 1 ? value : dealii::Utilities::MPI::sum(value, communicator);
  }

  double
  GrainPartition::max(const double value) const
  {
    return size == 1 ? value : dealii::Utilities::MPI::max(value, communicator);
  }

  void
  GrainPartition::sum(std::vector<unsigned int> &counts) const
  {
    if (size > 1)
      dealii::Utilities::MPI::sum(counts, communicator, counts);
  }
} // namespace sable::qusgm
