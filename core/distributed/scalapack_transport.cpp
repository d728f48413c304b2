#include "distributed/scalapack_transport.h"

#include <mpi.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "base/error.h"
#include "distributed/mpi_session.h"
#include "transport/text_format.h"

// BLACS, PBLAS and ScaLAPACK have no C header in Debian; these are their
// Fortran-callable entry points (PBLAS is C underneath, so no hidden string
// lengths; the one-character arguments of the Fortran routines are read as
// characters, as every C caller of ScaLAPACK does).
extern "C" {
void Cblacs_pinfo(int* rank, int* ranks);
void Cblacs_get(int context, int what, int* value);
void Cblacs_gridinit(int* context, const char* order, int rows, int cols);
void Cblacs_gridinfo(int context, int* rows, int* cols, int* row, int* col);
void Cblacs_gridexit(int context);
int numroc_(const int* n, const int* nb, const int* iproc, const int* isrcproc, const int* nprocs);
void descinit_(int* desc, const int* m, const int* n, const int* mb, const int* nb,
               const int* irsrc, const int* icsrc, const int* context, const int* lld, int* info);
void psgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
             const float* alpha, const float* a, const int* ia, const int* ja, const int* desca,
             const float* b, const int* ib, const int* jb, const int* descb, const float* beta,
             float* c, const int* ic, const int* jc, const int* descc);
void psgetrf_(const int* m, const int* n, float* a, const int* ia, const int* ja, const int* desca,
              int* ipiv, int* info);
void pdgetrf_(const int* m, const int* n, double* a, const int* ia, const int* ja, const int* desca,
              int* ipiv, int* info);
void psgetrs_(const char* trans, const int* n, const int* nrhs, const float* a, const int* ia,
              const int* ja, const int* desca, const int* ipiv, float* b, const int* ib,
              const int* jb, const int* descb, int* info);
void pdgetrs_(const char* trans, const int* n, const int* nrhs, const double* a, const int* ia,
              const int* ja, const int* desca, const int* ipiv, double* b, const int* ib,
              const int* jb, const int* descb, int* info);
}

namespace bounce {

namespace {

// Block size of the block-cyclic layout: ScaLAPACK's usual 64, large enough
// for the local BLAS 3 calls to run at speed, small enough to balance the
// ranks at a few hundred patches.
constexpr int kBlock = 64;
constexpr int kOne = 1, kZero = 0;
// float64 results with fewer than two correct digits are refused (as in
// inverse_transport.cpp).
constexpr double kFloat64ErrorLimit = 1e-2;

enum class Op : int { Stop = 0, Gemm = 1, Factor = 2, Solve = 3 };

struct Command {
  Op op = Op::Stop;
  int n = 0;
  float beta = 0.0f;
  int float64 = 0;
};

// Entries of one rank's share as one MPI message's count.
int message_count(int rows, int cols) {
  const auto count = static_cast<long long>(rows) * cols;
  if (count > std::numeric_limits<int>::max())
    throw Error("transport", text_format("distributed transport: a rank's %d x %d share exceeds "
                                         "one MPI message (use more ranks)",
                                         rows, cols));
  return static_cast<int>(count);
}

// Tag of the messages carrying a rank's share of a matrix.
constexpr int kShareTag = 9;

template <class Real>
MPI_Datatype mpi_type() {
  return sizeof(Real) == sizeof(double) ? MPI_DOUBLE : MPI_FLOAT;
}

struct Grid {
  int context = -1;
  int rank = 0, ranks = 1;
  int rows = 1, cols = 1, row = 0, col = 0;
  // Every rank's place on the grid: rank r at (row_of[r], col_of[r]).
  std::vector<int> row_of, col_of;

  Grid() {
    Cblacs_pinfo(&rank, &ranks);
    const ProcessGridShape shape = process_grid_shape(ranks);
    Cblacs_get(-1, 0, &context);
    Cblacs_gridinit(&context, "Row", shape.rows, shape.cols);
    Cblacs_gridinfo(context, &rows, &cols, &row, &col);
    if (row < 0 || col < 0)
      throw Error("ScaLAPACK", text_format("rank %d is not on the %d x %d process grid", rank,
                                           shape.rows, shape.cols));
    const int mine[2] = {row, col};
    std::vector<int> places(2 * static_cast<std::size_t>(ranks));
    mpi_check(MPI_Allgather(mine, 2, MPI_INT, places.data(), 2, MPI_INT, MPI_COMM_WORLD),
              "MPI_Allgather");
    for (int r = 0; r < ranks; ++r) {
      row_of.push_back(places[2 * static_cast<std::size_t>(r)]);
      col_of.push_back(places[2 * static_cast<std::size_t>(r) + 1]);
    }
  }
  ~Grid() {
    if (context >= 0) Cblacs_gridexit(context);
  }
  Grid(const Grid&) = delete;
  Grid& operator=(const Grid&) = delete;
};

// Global index of local index `local` on process `proc` of `procs` along one
// dimension (block-cyclic from process 0).
int global_index(int local, int proc, int procs) {
  return (local / kBlock * procs + proc) * kBlock + local % kBlock;
}

int local_count(int n, int proc, int procs) { return numroc_(&n, &kBlock, &proc, &kZero, &procs); }

// This rank's share of an n x n matrix.
template <class Real>
struct LocalMatrix {
  int n = 0, rows = 0, cols = 0, lld = 1;
  int desc[9] = {};
  std::vector<Real> a;  // column-major rows x cols, leading dimension lld
};

template <class Real>
LocalMatrix<Real> local_matrix(const Grid& g, int n) {
  LocalMatrix<Real> l;
  l.n = n;
  l.rows = local_count(n, g.row, g.rows);
  l.cols = local_count(n, g.col, g.cols);
  l.lld = std::max(1, l.rows);
  int info = 0;
  descinit_(l.desc, &n, &n, &kBlock, &kBlock, &kZero, &kZero, &g.context, &l.lld, &info);
  if (info != 0) throw Error("ScaLAPACK", text_format("descinit rejected argument %d", -info));
  l.a.assign(static_cast<std::size_t>(l.lld) * static_cast<std::size_t>(std::max(1, l.cols)),
             Real(0));
  return l;
}

// Applies `f(local, global)` to every entry of the share of an n x n matrix
// held by the process at (prow, pcol), local entries packed column-major with
// leading dimension `lld`.
template <class Visit>
void for_each_entry(int n, int prow, int pcol, const Grid& g, int lld, Visit&& f) {
  const int rows = local_count(n, prow, g.rows), cols = local_count(n, pcol, g.cols);
  const auto un = static_cast<std::size_t>(n);
  for (int jl = 0; jl < cols; ++jl) {
    const auto jg = static_cast<std::size_t>(global_index(jl, pcol, g.cols));
    for (int il = 0; il < rows; ++il) {
      const auto ig = static_cast<std::size_t>(global_index(il, prow, g.rows));
      f(static_cast<std::size_t>(jl) * static_cast<std::size_t>(lld) + static_cast<std::size_t>(il),
        jg * un + ig);
    }
  }
}

// Collective: every rank's block-cyclic share of the root's column-major
// n x n matrix `full` (read on the root only). The root packs and sends each
// rank its share alone, one rank at a time, so a rank never holds more than
// its share (about n^2 / ranks entries) and the root one share more than its
// own; a whole copy of the matrix exists on the root only.
LocalMatrix<float> scatter_from_root(const Grid& g, int n, const float* full) {
  LocalMatrix<float> share = local_matrix<float>(g, n);
  if (g.rank != 0) {
    mpi_check(MPI_Recv(share.a.data(), message_count(share.rows, share.cols), MPI_FLOAT, 0,
                       kShareTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
              "MPI_Recv of a matrix share");
    return share;
  }
  std::vector<float> packed;
  for (int r = 1; r < g.ranks; ++r) {
    const int rows = local_count(n, g.row_of[static_cast<std::size_t>(r)], g.rows);
    const int cols = local_count(n, g.col_of[static_cast<std::size_t>(r)], g.cols);
    const int count = message_count(rows, cols);
    packed.resize(static_cast<std::size_t>(count));
    for_each_entry(n, g.row_of[static_cast<std::size_t>(r)], g.col_of[static_cast<std::size_t>(r)],
                   g, std::max(1, rows),
                   [&](std::size_t local, std::size_t global) { packed[local] = full[global]; });
    mpi_check(MPI_Send(packed.data(), count, MPI_FLOAT, r, kShareTag, MPI_COMM_WORLD),
              "MPI_Send of a matrix share");
  }
  for_each_entry(n, g.row, g.col, g, share.lld,
                 [&](std::size_t local, std::size_t global) { share.a[local] = full[global]; });
  return share;
}

// The share of I - A (identity_minus) or A itself, in Real, from the float
// share of A; I - A formed as inverse_transport.cpp forms it (negate, then add
// 1 on the diagonal), so the entries are those the single process factorises.
template <class Real>
LocalMatrix<Real> converted(const LocalMatrix<float>& share, const Grid& g, bool identity_minus) {
  LocalMatrix<Real> l = local_matrix<Real>(g, share.n);
  for (int jl = 0; jl < l.cols; ++jl) {
    const int jg = global_index(jl, g.col, g.cols);
    for (int il = 0; il < l.rows; ++il) {
      const int ig = global_index(il, g.row, g.rows);
      const std::size_t at = static_cast<std::size_t>(jl) * static_cast<std::size_t>(l.lld) +
                             static_cast<std::size_t>(il);
      Real v = static_cast<Real>(share.a[at]);
      if (identity_minus) v = ig == jg ? -v + Real(1) : -v;
      l.a[at] = v;
    }
  }
  return l;
}

// Collective: every rank's share into the whole column-major matrix on the
// root (`full` is read on the root only), one rank's share at a time.
template <class Real>
void gather_to_root(const LocalMatrix<Real>& l, const Grid& g, float* full) {
  // lld = rows whenever the share has rows, so the local array is packed.
  if (g.rank != 0) {
    mpi_check(MPI_Send(l.a.data(), message_count(l.rows, l.cols), mpi_type<Real>(), 0, kShareTag,
                       MPI_COMM_WORLD),
              "MPI_Send of a result share");
    return;
  }
  for_each_entry(l.n, g.row, g.col, g, l.lld, [&](std::size_t local, std::size_t global) {
    full[global] = static_cast<float>(l.a[local]);
  });
  std::vector<Real> packed;
  for (int r = 1; r < g.ranks; ++r) {
    const int pr = g.row_of[static_cast<std::size_t>(r)],
              pc = g.col_of[static_cast<std::size_t>(r)];
    const int rows = local_count(l.n, pr, g.rows), cols = local_count(l.n, pc, g.cols);
    const int count = message_count(rows, cols);
    packed.resize(static_cast<std::size_t>(std::max(1, count)));
    mpi_check(MPI_Recv(packed.data(), count, mpi_type<Real>(), r, kShareTag, MPI_COMM_WORLD,
                       MPI_STATUS_IGNORE),
              "MPI_Recv of a result share");
    for_each_entry(l.n, pr, pc, g, std::max(1, rows), [&](std::size_t local, std::size_t global) {
      full[global] = static_cast<float>(packed[local]);
    });
  }
}

// Collective C = A B + beta C on row-major n x n buffers (read on the root).
void gemm_collective(const Grid& g, int n, float beta, const float* a, const float* b, float* c) {
  // Column-major, the buffers hold A^T, B^T, C^T: C^T = B^T A^T + beta C^T.
  LocalMatrix<float> la = scatter_from_root(g, n, a);
  LocalMatrix<float> lb = scatter_from_root(g, n, b);
  LocalMatrix<float> lc = beta != 0.0f ? scatter_from_root(g, n, c) : local_matrix<float>(g, n);
  const float one = 1.0f;
  psgemm_("N", "N", &n, &n, &n, &one, lb.a.data(), &kOne, &kOne, lb.desc, la.a.data(), &kOne, &kOne,
          la.desc, &beta, lc.a.data(), &kOne, &kOne, lc.desc);
  gather_to_root(lc, g, c);
}

template <class Real>
struct Pscalapack;

template <>
struct Pscalapack<float> {
  static void getrf(int n, float* a, const int* desc, int* ipiv, int* info) {
    psgetrf_(&n, &n, a, &kOne, &kOne, desc, ipiv, info);
  }
  static void getrs(int n, const float* a, const int* desca, const int* ipiv, float* b,
                    const int* descb, int* info) {
    psgetrs_("N", &n, &n, a, &kOne, &kOne, desca, ipiv, b, &kOne, &kOne, descb, info);
  }
};

template <>
struct Pscalapack<double> {
  static void getrf(int n, double* a, const int* desc, int* ipiv, int* info) {
    pdgetrf_(&n, &n, a, &kOne, &kOne, desc, ipiv, info);
  }
  static void getrs(int n, const double* a, const int* desca, const int* ipiv, double* b,
                    const int* descb, int* info) {
    pdgetrs_("N", &n, &n, a, &kOne, &kOne, desca, ipiv, b, &kOne, &kOne, descb, info);
  }
};

// The factorisation of I - M^T kept between the Factor and Solve commands,
// with the share of the right-hand side M^T.
struct SolveState {
  int n = 0;
  bool float64 = false;
  LocalMatrix<float> lu32, rhs32;
  LocalMatrix<double> lu64, rhs64;
  std::vector<int> ipiv;
  int info = 0;  // of the factorisation: 0, or the zero pivot (> 0)
};

template <class Real>
void factor_collective(const Grid& g, SolveState& s, LocalMatrix<Real>& lu, LocalMatrix<Real>& rhs,
                       LocalMatrix<float> share) {
  lu = converted<Real>(share, g, true);
  if constexpr (std::is_same_v<Real, float>)
    rhs = std::move(share);
  else
    rhs = converted<Real>(share, g, false);
  s.ipiv.assign(static_cast<std::size_t>(lu.rows + kBlock), 0);
  Pscalapack<Real>::getrf(s.n, lu.a.data(), lu.desc, s.ipiv.data(), &s.info);
}

// Command Factor: each rank receives its share of the root's M (row-major,
// read column-major as M^T); all factorise I - M^T.
void factor(const Grid& g, SolveState& s, const Command& c, const float* m) {
  s = SolveState{};
  s.n = c.n;
  s.float64 = c.float64 != 0;
  LocalMatrix<float> share = scatter_from_root(g, c.n, m);
  if (s.float64)
    factor_collective<double>(g, s, s.lu64, s.rhs64, std::move(share));
  else
    factor_collective<float>(g, s, s.lu32, s.rhs32, std::move(share));
}

// kappa_inf(I - M) = ||I - M||_inf ||(I - M)^-1||_inf, computed, not
// estimated: (I - M)^-1 = I + T with T the solution. (ScaLAPACK's p?gecon,
// tried first, returned about a third of this on the Cornell box, where
// LAPACK's ?gecon matches it.) t and m are row-major n x n.
double condition_from_solution(const std::vector<float>& t, const std::vector<float>& m,
                               std::size_t n) {
  double anorm = 0.0, inverse_norm = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    double row = 0.0, inverse_row = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      const double v = m[i * n + j], x = t[i * n + j];
      row += i == j ? std::abs(1.0 - v) : std::abs(v);
      inverse_row += i == j ? std::abs(1.0 + x) : std::abs(x);
    }
    anorm = std::max(anorm, row);
    inverse_norm = std::max(inverse_norm, inverse_row);
  }
  return anorm * inverse_norm;
}

// Command Solve: every rank solves its share; the root gathers T (row-major)
// into t.
void solve(const Grid& g, SolveState& s, float* t) {
  if (s.float64) {
    Pscalapack<double>::getrs(s.n, s.lu64.a.data(), s.lu64.desc, s.ipiv.data(), s.rhs64.a.data(),
                              s.rhs64.desc, &s.info);
    if (s.info == 0) gather_to_root(s.rhs64, g, t);
  } else {
    Pscalapack<float>::getrs(s.n, s.lu32.a.data(), s.lu32.desc, s.ipiv.data(), s.rhs32.a.data(),
                             s.rhs32.desc, &s.info);
    if (s.info == 0) gather_to_root(s.rhs32, g, t);
  }
}

void check_info(int info, const char* routine) {
  if (info < 0) throw Error("transport", text_format("%s rejected argument %d", routine, -info));
  if (info > 0)
    throw Error("transport",
                text_format("%s: I - diag(albedo) F is exactly singular (zero pivot %d): light "
                            "would grow without bound; check form-factor row sums and albedo",
                            routine, info));
}

void send(const Command& c) {
  Command copy = c;
  mpi_check(MPI_Bcast(&copy, sizeof copy, MPI_BYTE, 0, MPI_COMM_WORLD), "MPI_Bcast");
}

class ScalapackGemm : public GemmBackend {
 public:
  explicit ScalapackGemm(const Grid& g) : grid_(g) {}
  std::string name() const override {
    return text_format("ScaLAPACK psgemm (%d ranks, %d x %d grid)", grid_.ranks, grid_.rows,
                       grid_.cols);
  }
  void multiply(std::size_t n, const float* a, const float* b, float beta, float* c) override {
    Command cmd;
    cmd.op = Op::Gemm;
    cmd.n = static_cast<int>(n);
    cmd.beta = beta;
    if (cmd.n < 0 || static_cast<std::size_t>(cmd.n) != n)
      throw Error("transport", "distributed product: n exceeds the 32-bit ScaLAPACK interface");
    send(cmd);
    gemm_collective(grid_, cmd.n, beta, a, b, c);
  }

 private:
  const Grid& grid_;
};

class ScalapackExecutor : public TransportExecutor {
 public:
  ScalapackExecutor() : gemm_(grid_) {}
  ~ScalapackExecutor() override {
    try {
      send(Command{});  // Stop: the other ranks return from serve
    } catch (...) {
      // An MPI failure here leaves nothing to release; mpirun ends the job.
    }
  }
  GemmBackend& gemm() override { return gemm_; }
  std::string description() const override {
    return text_format(
        "ScaLAPACK (p?gemm, p?getrf/p?getrs) on %d MPI ranks, a %d x %d "
        "process grid, %d x %d blocks",
        grid_.ranks, grid_.rows, grid_.cols, kBlock, kBlock);
  }

  InverseTransport solve_infinite(std::vector<float> m, std::size_t n, double spectral_radius,
                                  const InverseOptions& options) override {
    if (m.size() != n * n) throw Error("transport", "solve_infinite: size does not match n");
    InverseTransport r;
    if (n == 0) return r;
    // The precision rule of inverse_transport.cpp, decided here on the root.
    r.condition_lower_bound = condition_lower_bound(m.data(), n, spectral_radius);
    const double limit = options.float32_error_limit;
    PrecisionChoice choice = precision_before_factorising(r.condition_lower_bound, options);
    bool use_float64 = choice.precision == TransportPrecision::Float64;
    r.why = std::move(choice.why);
    // Unlike the single process, which decides from an estimate before
    // solving, the float32 solution is computed first: it gives the exact
    // condition number, and M (kept) is solved again in float64 if that fails
    // the rule.
    Command cmd;
    cmd.op = Op::Factor;
    cmd.n = static_cast<int>(n);
    std::vector<float> m_kept = m;
    if (!use_float64) {
      send(cmd);
      factor(grid_, state_, cmd, m.data());
      check_info(state_.info, "psgetrf");
      if (options.tick) options.tick();  // factorised
      std::vector<float> t = solve_here(std::move(m));
      r.condition = condition_from_solution(t, m_kept, n);
      if (!options.force && r.condition * FLT_EPSILON > limit) {
        use_float64 = true;
        r.refactorised = true;
        r.why = text_format(
            "float64: float32 LU's condition %.3g gives kappa * eps = %.2g > %.0e "
            "(the lower bound %.3g had allowed float32); refactorised",
            r.condition, r.condition * FLT_EPSILON, limit, r.condition_lower_bound);
        m = m_kept;
      } else {
        if (!options.force)
          r.why = text_format("float32: condition %.3g gives kappa * eps = %.2g <= %.0e",
                              r.condition, r.condition * FLT_EPSILON, limit);
        for (int b = 0; b < options.solve_blocks; ++b)
          if (options.tick) options.tick();
        r.precision = TransportPrecision::Float32;
        r.t = std::move(t);
        return r;
      }
    }
    cmd.float64 = 1;
    send(cmd);
    factor(grid_, state_, cmd, m.data());
    check_info(state_.info, "pdgetrf");
    if (options.tick && !r.refactorised) options.tick();  // factorised
    std::vector<float> t = solve_here(std::move(m));
    r.condition = condition_from_solution(t, m_kept, n);
    if (r.condition * DBL_EPSILON > kFloat64ErrorLimit)
      throw Error("transport", text_format("I - diag(albedo) F is numerically singular (condition "
                                           "%.3g): check form-factor row sums and albedo",
                                           r.condition));
    for (int b = 0; b < options.solve_blocks; ++b)
      if (options.tick) options.tick();
    r.precision = TransportPrecision::Float64;
    r.t = std::move(t);
    return r;
  }

 private:
  // Solves with the factorisation in state_ on every rank; T overwrites m's
  // buffer.
  std::vector<float> solve_here(std::vector<float> m) {
    Command cmd;
    cmd.op = Op::Solve;
    send(cmd);
    solve(grid_, state_, m.data());
    check_info(state_.info, "p?getrs");
    state_ = SolveState{};
    return m;
  }

  Grid grid_;
  ScalapackGemm gemm_;
  SolveState state_;
};

}  // namespace

ProcessGridShape process_grid_shape(int ranks) {
  ProcessGridShape s;
  s.rows = 1;
  for (int r = 1; r * r <= ranks; ++r)
    if (ranks % r == 0) s.rows = r;
  s.cols = ranks / s.rows;
  return s;
}

std::unique_ptr<TransportExecutor> make_scalapack_executor() {
  return std::make_unique<ScalapackExecutor>();
}

void serve_scalapack_transport() {
  const Grid grid;
  SolveState state;
  for (;;) {
    Command cmd;
    mpi_check(MPI_Bcast(&cmd, sizeof cmd, MPI_BYTE, 0, MPI_COMM_WORLD), "MPI_Bcast");
    switch (cmd.op) {
      case Op::Stop:
        return;
      case Op::Gemm:
        gemm_collective(grid, cmd.n, cmd.beta, nullptr, nullptr, nullptr);
        break;
      case Op::Factor:
        factor(grid, state, cmd, nullptr);
        break;
      case Op::Solve:
        solve(grid, state, nullptr);
        state = SolveState{};
        break;
    }
  }
}

}  // namespace bounce
