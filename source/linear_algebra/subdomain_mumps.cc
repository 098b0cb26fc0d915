#include <deal.II/base/mpi.h>

#include <bsmpm/linear_algebra/subdomain_mumps.h>

#include <Epetra_Map.h>
#include <Epetra_MpiComm.h>

#include <algorithm>
#include <unordered_map>

namespace bsmpm
{
  namespace
  {
    /** The blocks of @p values (block p of @p sizes[p] entries) of every
     * process on process 0, in the order of the processes. */
    std::vector<double>
    gather_blocks(const MPI_Comm             communicator,
                  const std::vector<double> &values,
                  const std::vector<int>    &sizes)
    {
      const bool host = Utilities::MPI::this_mpi_process(communicator) == 0;
      std::vector<int>    offsets;
      std::vector<double> all;
      if (host)
        {
          offsets.resize(sizes.size() + 1, 0);
          for (std::size_t p = 0; p < sizes.size(); ++p)
            offsets[p + 1] = offsets[p] + sizes[p];
          all.resize(offsets.back());
        }
      const int error = MPI_Gatherv(values.data(),
                                    values.size(),
                                    MPI_DOUBLE,
                                    all.data(),
                                    sizes.data(),
                                    offsets.data(),
                                    MPI_DOUBLE,
                                    0,
                                    communicator);
      AssertThrowMPI(error);
      return all;
    }
  } // namespace



  SubdomainMumps::SubdomainMumps(const Epetra_CrsMatrix &matrix,
                                 const bool              symmetric)
    : communicator(dynamic_cast<const Epetra_MpiComm &>(matrix.Comm()).Comm())
    , this_process(Utilities::MPI::this_mpi_process(communicator))
    , symmetric(symmetric)
  {}



  /** What factorize() finds out about the matrix's structure on the way
   * to the local unknowns and the triplets. */
  struct SubdomainMumps::Structure
  {
    explicit Structure(const Epetra_CrsMatrix &matrix)
      : matrix(matrix)
    {}

    /** The column indices of local row @p row. */
    std::pair<int, int *>
    row_columns(const int row) const
    {
      int  n       = 0;
      int *indices = nullptr;
      matrix.Graph().ExtractMyRowView(row, n, indices);
      return std::make_pair(n, indices);
    }

    /** The code of local row @p row: its interior index (>= 0) or -1 -
     * its interface number. */
    int
    code_of_row(const int row) const
    {
      return on_interface[row] ? -1 - number_of.at(matrix.GRID(row)) :
                                 interior[row];
    }

    const Epetra_CrsMatrix &matrix;
    /** By local column: its global id, the process that owns it and its
     * row there. */
    std::vector<int> column_ids, owner, owner_row;
    /** By local row: whether it is an interface row; its interior index
     * (-1 on the interface). */
    std::vector<char> on_interface;
    std::vector<int>  interior;
    /** The global ids of this process' interface rows, and the interface
     * number of every interface id. */
    std::vector<int>             own_interface;
    std::unordered_map<int, int> number_of;
    /** The local entries as pairs of codes (code_of_row()). */
    std::vector<std::pair<int, int>> entries;
  };



  DirectSolver::Status
  SubdomainMumps::factorize(const Epetra_CrsMatrix &matrix)
  {
    Structure structure(matrix);
    find_interface(structure);
    if (n_interface > max_interface_size)
      return DirectSolver::Status::other;
    collect_entries(structure);
    number_local_unknowns(structure);
    const DirectSolver::Status status = analyse();
    if (status != DirectSolver::Status::success)
      return status;
    return refactorize(matrix);
  }



  void
  SubdomainMumps::find_interface(Structure &structure)
  {
    const Epetra_CrsMatrix &matrix    = structure.matrix;
    const Epetra_Map       &row_map   = matrix.RowMap();
    const Epetra_Map       &col_map   = matrix.ColMap();
    const int               n_rows    = matrix.NumMyRows();
    const int               n_columns = col_map.NumMyElements();

    // The process that owns each column (collective).
    auto &column_ids = structure.column_ids;
    auto &owner      = structure.owner;
    column_ids.resize(n_columns);
    owner.resize(n_columns);
    structure.owner_row.resize(n_columns);
    col_map.MyGlobalElements(column_ids.data());
    row_map.RemoteIDList(n_columns,
                         column_ids.data(),
                         owner.data(),
                         structure.owner_row.data());

    // 1. The interface: rows with a column of a later process, and rows
    //    that a later process' row has a column in (told their owner).
    auto &on_interface = structure.on_interface;
    on_interface.assign(n_rows, 0);
    std::map<unsigned int, std::vector<int>> told;
    for (int row = 0; row < n_rows; ++row)
      {
        const auto [n, indices] = structure.row_columns(row);
        for (int k = 0; k < n; ++k)
          {
            const unsigned int o = owner[indices[k]];
            if (o > this_process)
              on_interface[row] = 1;
            else if (o < this_process)
              told[o].push_back(column_ids[indices[k]]);
          }
      }
    for (auto &[process, ids] : told)
      {
        (void)process;
        std::sort(ids.begin(), ids.end());
        ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
      }
    for (const auto &[process, ids] :
         Utilities::MPI::some_to_some(communicator, told))
      {
        (void)process;
        for (const int id : ids)
          on_interface[row_map.LID(id)] = 1;
      }

    // 2. Interface numbers over all processes; every process knows them
    //    (a few hundred to a few thousand ids).
    for (int row = 0; row < n_rows; ++row)
      if (on_interface[row])
        structure.own_interface.push_back(matrix.GRID(row));
    const std::vector<std::vector<int>> all_interface =
      Utilities::MPI::all_gather(communicator, structure.own_interface);
    for (const auto &ids : all_interface)
      for (const int id : ids)
        structure.number_of.emplace(id, structure.number_of.size());
    n_interface = structure.number_of.size();
  }



  void
  SubdomainMumps::collect_entries(Structure &structure)
  {
    // 3. The local entries, each as a pair of codes: an interior index
    //    (>= 0) or -1 - an interface number. Entries of an interface row
    //    of this process in another process' interior go there.
    const Epetra_CrsMatrix &matrix = structure.matrix;
    const int               n_rows = matrix.NumMyRows();
    structure.interior.assign(n_rows, -1);
    n_interior = 0;
    for (int row = 0; row < n_rows; ++row)
      if (!structure.on_interface[row])
        structure.interior[row] = n_interior++;
    const auto                              &owner      = structure.owner;
    const auto                              &column_ids = structure.column_ids;
    const auto                              &number_of  = structure.number_of;
    auto                                    &entries    = structure.entries;
    std::map<unsigned int, std::vector<int>> sent_ids;
    value_position.clear();
    sent_entries.clear();
    for (int row = 0; row < n_rows; ++row)
      {
        const int row_code      = structure.code_of_row(row);
        const auto [n, indices] = structure.row_columns(row);
        for (int k = 0; k < n; ++k)
          {
            const int c = indices[k];
            int       column_code;
            if (owner[c] == static_cast<int>(this_process))
              column_code = structure.code_of_row(structure.owner_row[c]);
            else if (const auto it = number_of.find(column_ids[c]);
                     it != number_of.end())
              column_code = -1 - it->second;
            else
              {
                // Only an interface row couples to another interior.
                AssertThrow(row_code < 0, ExcInternalError());
                sent_ids[owner[c]].push_back(matrix.GRID(row));
                sent_ids[owner[c]].push_back(column_ids[c]);
                sent_entries[owner[c]].push_back(value_position.size());
                value_position.push_back(-1);
                continue;
              }
            value_position.push_back(entries.size());
            entries.emplace_back(row_code, column_code);
          }
      }
    received_positions.clear();
    for (const auto &[process, ids] :
         Utilities::MPI::some_to_some(communicator, sent_ids))
      for (std::size_t m = 0; m + 1 < ids.size(); m += 2)
        {
          const int column =
            structure.interior[matrix.RowMap().LID(ids[m + 1])];
          AssertThrow(column >= 0, ExcInternalError());
          received_positions[process].push_back(entries.size());
          entries.emplace_back(-1 - number_of.at(ids[m]), column);
        }
  }



  int
  SubdomainMumps::local_of(const int code) const
  {
    return code >= 0 ?
             code :
             n_interior +
               static_cast<int>(
                 std::lower_bound(touched.begin(), touched.end(), -1 - code) -
                 touched.begin());
  }



  void
  SubdomainMumps::number_local_unknowns(const Structure &structure)
  {
    // 4. The local unknowns: the interior, then the interface unknowns
    //    this process touches, ascending.
    const auto &entries = structure.entries;
    touched.clear();
    for (const int id : structure.own_interface)
      touched.push_back(structure.number_of.at(id));
    for (const auto &[r, c] : entries)
      for (const int code : {r, c})
        if (code < 0)
          touched.push_back(-1 - code);
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    const int n_rows = structure.matrix.NumMyRows();
    local_index.resize(n_rows);
    for (int row = 0; row < n_rows; ++row)
      local_index[row] = local_of(structure.code_of_row(row));

    // 5. The triplets (one triangle of a symmetric matrix), and where each
    //    entry's value goes among them.
    triplet_rows.clear();
    triplet_columns.clear();
    std::vector<int> kept(entries.size(), -1);
    for (std::size_t e = 0; e < entries.size(); ++e)
      {
        const int r = local_of(entries[e].first) + 1;
        const int c = local_of(entries[e].second) + 1;
        if (!symmetric || c <= r)
          {
            kept[e] = triplet_rows.size();
            triplet_rows.push_back(r);
            triplet_columns.push_back(c);
          }
      }
    for (int &position : value_position)
      if (position >= 0)
        position = kept[position];
    for (auto &[process, positions] : received_positions)
      {
        (void)process;
        for (int &position : positions)
          position = kept[position];
      }
  }



  DirectSolver::Status
  SubdomainMumps::analyse()
  {
    // 6. The analyses: the local matrix with the touched interface as its
    //    Schur complement, and the dense S on process 0.
    const int n_touched = touched.size();
    int       status    = static_cast<int>(DirectSolver::Status::success);
    local.reset();
    if (n_interior > 0)
      {
        local  = std::make_unique<MumpsFactorization>(symmetric);
        status = static_cast<int>(local->analyse(
          n_interior + n_touched, triplet_rows, triplet_columns, n_touched));
      }
    touched_by_process = Utilities::MPI::gather(communicator, touched, 0);
    interface.reset();
    if (this_process == 0 && status == 0 && n_interface > 0)
      {
        std::vector<int> rows, columns;
        for (int i = 0; i < n_interface; ++i)
          for (int j = 0; j < (symmetric ? i + 1 : n_interface); ++j)
            {
              rows.push_back(i + 1);
              columns.push_back(j + 1);
            }
        interface = std::make_unique<MumpsFactorization>(symmetric);
        // Round-off of the summed S: 1e-14 of its largest entry told the
        // pure Neumann problem; a thin IBM band (delta / h = 1e-6) leaves
        // pivots of about 1e-7 of it.
        interface->set_null_pivot_threshold(1e-11);
        status =
          static_cast<int>(interface->analyse(n_interface, rows, columns));
      }
    return static_cast<DirectSolver::Status>(
      Utilities::MPI::max(status, communicator));
  }



  DirectSolver::Status
  SubdomainMumps::refactorize(const Epetra_CrsMatrix &matrix)
  {
    const bool same = collect_values(matrix);
    if (Utilities::MPI::min(same ? 1 : 0, communicator) == 0)
      return DirectSolver::Status::other;
    return factorize_interface(local ? local->factorize(values) :
                                       DirectSolver::Status::success);
  }



  bool
  SubdomainMumps::collect_values(const Epetra_CrsMatrix &matrix)
  {
    flat_values.clear();
    for (int row = 0; row < matrix.NumMyRows(); ++row)
      {
        int     n       = 0;
        double *entries = nullptr;
        matrix.ExtractMyRowView(row, n, entries);
        flat_values.insert(flat_values.end(), entries, entries + n);
      }
    // Every process takes part in the exchange before any says no.
    bool same = flat_values.size() == value_position.size();
    std::map<unsigned int, std::vector<double>> outgoing;
    for (const auto &[process, positions] : sent_entries)
      for (const int p : positions)
        outgoing[process].push_back(same ? flat_values[p] : 0.);
    const auto incoming = Utilities::MPI::some_to_some(communicator, outgoing);
    if (!same || incoming.size() != received_positions.size())
      return false;

    values.assign(triplet_rows.size(), 0.);
    for (std::size_t p = 0; p < flat_values.size(); ++p)
      if (value_position[p] >= 0)
        values[value_position[p]] = flat_values[p];
    for (const auto &[process, data] : incoming)
      {
        const auto it = received_positions.find(process);
        if (it == received_positions.end() || it->second.size() != data.size())
          return false;
        for (std::size_t m = 0; m < data.size(); ++m)
          if (it->second[m] >= 0)
            values[it->second[m]] = data[m];
      }
    return true;
  }



  DirectSolver::Status
  SubdomainMumps::factorize_interface(const DirectSolver::Status local_status)
  {
    int status =
      Utilities::MPI::max(static_cast<int>(local_status), communicator);
    if (status != 0)
      return static_cast<DirectSolver::Status>(status);

    // S_p: MUMPS' Schur complement, or the local entries themselves where
    // this process has no interior unknowns.
    const int           n_touched = touched.size();
    std::vector<double> own_part;
    if (local)
      {
        if (n_touched > 0)
          own_part = local->schur_complement();
      }
    else
      {
        own_part.assign(static_cast<std::size_t>(n_touched) * n_touched, 0.);
        for (std::size_t e = 0; e < values.size(); ++e)
          own_part[(triplet_rows[e] - 1) * n_touched + triplet_columns[e] -
                   1] += values[e];
      }
    std::vector<int> sizes;
    if (this_process == 0)
      for (const auto &t : touched_by_process)
        sizes.push_back(t.size() * t.size());
    const std::vector<double> parts =
      gather_blocks(communicator, own_part, sizes);

    if (this_process == 0 && interface)
      {
        // S = sum_p S_p, in the order of the processes, straight into the
        // entries of S's triplets (by rows; the lower triangle if
        // symmetric, as analysed in factorize()).
        const auto entry = [&](const std::size_t i, const std::size_t j) {
          return symmetric ? i * (i + 1) / 2 + j : i * n_interface + j;
        };
        interface_entries.assign(entry(n_interface - 1, n_interface - 1) + 1,
                                 0.);
        std::size_t offset = 0;
        for (const auto &t : touched_by_process)
          {
            const std::size_t m = t.size();
            for (std::size_t a = 0; a < m; ++a)
              for (std::size_t b = 0; b < (symmetric ? a + 1 : m); ++b)
                interface_entries[entry(t[a], t[b])] +=
                  parts[offset + a * m + b];
            offset += m * m;
          }
        status = static_cast<int>(interface->factorize(interface_entries));
      }
    return static_cast<DirectSolver::Status>(
      Utilities::MPI::broadcast(communicator, status, 0));
  }



  bool
  SubdomainMumps::solve(Epetra_MultiVector &x, const Epetra_MultiVector &b)
  {
    const int n_rows    = local_index.size();
    const int n_touched = touched.size();
    local_rhs.assign(n_interior + n_touched, 0.);
    for (int row = 0; row < n_rows; ++row)
      local_rhs[local_index[row]] = b[0][row];

    // The right-hand side reduced onto the interface, summed on process 0.
    bool ok = true;
    reduced.assign(n_touched, 0.);
    if (local && n_touched > 0)
      ok = local->reduce(local_rhs.data(), reduced.data());
    else if (local)
      ok = local->solve(local_rhs.data());
    else
      std::copy(local_rhs.begin(), local_rhs.end(), reduced.begin());
    std::vector<int> sizes;
    if (this_process == 0)
      for (const auto &t : touched_by_process)
        sizes.push_back(t.size());
    const std::vector<double> parts =
      gather_blocks(communicator, reduced, sizes);

    // S x_G = g on process 0, and each process' part of x_G sent back.
    std::vector<double> interface_solution(n_interface, 0.), send;
    std::vector<int>    offsets;
    if (this_process == 0)
      {
        std::size_t offset = 0;
        for (const auto &t : touched_by_process)
          {
            for (std::size_t a = 0; a < t.size(); ++a)
              interface_solution[t[a]] += parts[offset + a];
            offset += t.size();
          }
        if (interface)
          ok = interface->solve(interface_solution.data()) && ok;
        offsets.push_back(0);
        for (const auto &t : touched_by_process)
          {
            for (const int s : t)
              send.push_back(interface_solution[s]);
            offsets.push_back(send.size());
          }
      }
    const int error = MPI_Scatterv(send.data(),
                                   sizes.data(),
                                   offsets.data(),
                                   MPI_DOUBLE,
                                   reduced.data(),
                                   n_touched,
                                   MPI_DOUBLE,
                                   0,
                                   communicator);
    AssertThrowMPI(error);

    // The interiors from the interface's values.
    if (local && n_touched > 0)
      ok = local->expand(local_rhs.data(), reduced.data()) && ok;
    std::copy(reduced.begin(), reduced.end(), local_rhs.begin() + n_interior);
    for (int row = 0; row < n_rows; ++row)
      x[0][row] = local_rhs[local_index[row]];
    return Utilities::MPI::min(ok ? 1 : 0, communicator) == 1;
  }
} // namespace bsmpm
