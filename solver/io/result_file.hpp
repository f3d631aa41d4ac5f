// The result file of one simulation run: an HDF5 file with time histories and
// field snapshots, and an XDMF companion (.xmf, same stem, same folder) so that
// ParaView opens the snapshots as a time series.
//
// Layout (format_version 1; every numeric dataset carries a text attribute "unit"):
//   /                                 attributes: format = "splat-result", format_version,
//                                     and those given to set_attribute; a number with a
//                                     unit is stored as <name> plus a text <name>_unit
//   /bodies/<body>/connectivity       int32, cells x nodes-per-cell, fixed for the run;
//                                     attributes cell_kind (quad4 | hex8 | point),
//                                     dimension (2 | 3), num_nodes. Point bodies get
//                                     the trivial connectivity 0..n-1 (n x 1).
//   /history/<column>                 float64, one value per history row, extendible
//   /snapshots/<k>                    k = 0, 1, ...; attributes time and time_unit = "s"
//   /snapshots/<k>/<body>/coordinates float64, num_nodes x dimension, unit "m"
//   /snapshots/<k>/<body>/<field>     float64, num_items (x components); attribute
//                                     center = "node" | "cell" ("node" for every field
//                                     of a point body: its cells are its nodes)
//   /snapshots/<k>/<body>/active      int32, one per cell, 1 = live, 0 = eroded
//   /snapshots/<k>/<body>/eroded      int32, 1 - active (what the .xmf shows)
//
// The .xmf: one temporal collection; each time step a spatial collection of
// one uniform grid per body (Quadrilateral, Hexahedron, or Polyvertex with
// point data). Attribute names carry the unit, "temperature [K]" (bare name
// when dimensionless); each refers to its dataset above.
// Groups track link creation order, so bodies, columns and fields list in the
// order they were written.
//
// Crash safety: the file is flushed after construction, after each snapshot and
// every k_history_flush_rows history rows, and the .xmf is replaced atomically
// (temp file + rename) after each snapshot, so a process cut after a completed
// snapshot leaves a readable pair. A file without snapshots has no .xmf (the
// constructor removes one left by an earlier run).
//
// HDF5 failures (and a .xmf that cannot be written) throw ResultFileError (a
// std::runtime_error) naming the file and the object path;
// bad arguments throw std::invalid_argument; use after close() throws
// std::logic_error. All calls into HDF5 from this module are serialised.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace splat {

// The result file could not be written or read (a full disk, a file cut
// short): a fault of the file system, not of the scene.
class ResultFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// XDMF Quadrilateral, Hexahedron, Polyvertex. Node order per cell is that of
// VTK/XDMF: quads counter-clockwise, hexahedra bottom face then top face.
enum class CellKind { quad4, hex8, point };

struct BodyTopology {
  std::string name;  // [A-Za-z0-9_.+-]+, unique among the bodies
  CellKind kind = CellKind::quad4;
  int dimension = 2;              // 2: axisymmetric (r, z); 3: (x, y, z)
  std::vector<int> connectivity;  // flattened, 4 or 8 node indices per cell; empty for points
  std::size_t num_nodes = 0;
};

struct FieldView {
  std::string name;  // [A-Za-z0-9_.+-]+, not "coordinates", "active" or "eroded"
  std::string unit;
  bool on_cells = false;  // cell field (else node field)
  // 1 scalar, 2 or 3 vector, 6 symmetric tensor in XDMF Tensor6 order
  // (xx, xy, xz, yy, yz, zz), 9 full tensor (row-major).
  int components = 1;
  std::span<const double> values;  // row-major, num_items x components
};

struct BodySnapshot {
  std::string body;
  std::span<const double> coordinates;  // num_nodes x dimension, m
  std::vector<FieldView> fields;
  std::span<const int> active_cells;  // one 0/1 per cell, or empty (no "active" dataset)
};

// Rows between two flushes of the history to disk; also the chunk length.
inline constexpr std::size_t k_history_flush_rows = 1024;

// Writes one run's result file. Not thread-safe per object; separate objects
// may be used from separate threads.
class ResultFile {
 public:
  // Creates (truncates) h5_path and writes the bodies' topology and the empty
  // history columns; removes a stale .xmf (the first snapshot writes it).
  ResultFile(const std::filesystem::path& h5_path, std::vector<BodyTopology> bodies,
             std::vector<std::pair<std::string, std::string>> history_columns /* name, unit */);
  ResultFile(ResultFile&&) noexcept;
  ResultFile& operator=(ResultFile&&) noexcept;
  ResultFile(const ResultFile&) = delete;
  ResultFile& operator=(const ResultFile&) = delete;
  ~ResultFile();  // calls close(); reports a failure on stderr, never throws

  // Root attributes (solver_version, outcome, reason, ...); setting one again replaces it.
  void set_attribute(const std::string& name, const std::string& value);
  void set_attribute(const std::string& name, double value, const std::string& unit);
  void set_attribute(const std::string& name, long long value);
  // A real number needs its unit; without this a double would silently become long long.
  void set_attribute(const std::string& name, double value) = delete;

  // One value per history column, in the constructor's column order. Buffered.
  void append_history(std::span<const double> row);

  // Writes snapshot k = number written so far. Every body appears exactly once;
  // time (s) is finite and not below the previous snapshot's.
  void write_snapshot(double time, std::span<const BodySnapshot> bodies);

  // Flushes the history, writes the .xmf (if there are snapshots) and closes
  // the file. Idempotent.
  void close();

  const std::filesystem::path& h5_path() const;
  const std::filesystem::path& xmf_path() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The .xmf that belongs to a result file: same folder and stem.
std::filesystem::path xmf_path_for(const std::filesystem::path& h5_path);

// Reading back. Integer root attributes appear among number_attributes.
struct ResultSummary {
  std::map<std::string, std::string> text_attributes;
  std::map<std::string, double> number_attributes;
  std::vector<std::string> history_columns;  // in the order they were created
  std::size_t history_rows = 0;
  std::size_t snapshots = 0;
};

ResultSummary read_result_summary(const std::filesystem::path& h5_path);
std::vector<double> read_history(const std::filesystem::path& h5_path, const std::string& column);
// The "unit" attribute of the dataset or group at dataset_path ("/history/energy").
std::string read_unit(const std::filesystem::path& h5_path, const std::string& dataset_path);
// Row-major values; field may be "coordinates" or "active".
std::vector<double> read_snapshot_field(const std::filesystem::path& h5_path, std::size_t snapshot,
                                        const std::string& body, const std::string& field);
double read_snapshot_time(const std::filesystem::path& h5_path, std::size_t snapshot);
// /bodies/<body>/connectivity, flattened (for point bodies 0..n-1).
std::vector<int> read_connectivity(const std::filesystem::path& h5_path, const std::string& body);
// The shape of the dataset at object_path, or nullopt if there is no dataset there.
std::optional<std::vector<std::size_t>> read_dataset_shape(const std::filesystem::path& h5_path,
                                                           const std::string& object_path);

}  // namespace splat
