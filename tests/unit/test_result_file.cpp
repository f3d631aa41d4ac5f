// The HDF5 result file and its XDMF companion round-trip: attributes, a long
// history, and snapshots of a 2D quad body and a 3D hex body are read back
// bit for bit, and every dataset the .xmf names exists with the stated shape.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/io/result_file.hpp"

namespace splat {
namespace {

namespace fs = std::filesystem;

// A fresh directory under the system temp directory, removed on scope exit.
class TempDir {
 public:
  TempDir() {
    std::random_device rd;
    const auto tag = std::to_string(rd()) + "_" + std::to_string(rd());
    path_ = fs::temp_directory_path() / ("splat_result_file_" + tag);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// nx x ny quads on [0, nx] x [0, ny], counter-clockwise.
BodyTopology quad_grid(const std::string& name, int nx, int ny) {
  BodyTopology t{name, CellKind::quad4, 2, {}, static_cast<std::size_t>((nx + 1) * (ny + 1))};
  auto node = [&](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      for (int n : {node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)}) {
        t.connectivity.push_back(n);
      }
    }
  }
  return t;
}

// nx x ny x nz unit-cube hexahedra, VTK node order.
BodyTopology hex_grid(const std::string& name, int nx, int ny, int nz) {
  BodyTopology t{
      name, CellKind::hex8, 3, {}, static_cast<std::size_t>((nx + 1) * (ny + 1) * (nz + 1))};
  auto node = [&](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        for (int n : {node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k), node(i, j + 1, k),
                      node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1),
                      node(i, j + 1, k + 1)}) {
          t.connectivity.push_back(n);
        }
      }
    }
  }
  return t;
}

std::size_t cell_count(const BodyTopology& t) {
  return t.connectivity.size() / (t.kind == CellKind::quad4 ? 4 : 8);
}

// Values with full mantissas and a spread of magnitudes, so that any rounding shows.
std::vector<double> values(std::size_t n, double seed) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = static_cast<double>(i);
    v[i] = std::sin(seed + 0.37 * x) * std::pow(10.0, std::fmod(x, 7.0) - 3.0) + seed / 3.0;
  }
  return v;
}

// The data of one body at one snapshot, kept alive while the spans point into it.
struct BodyData {
  std::vector<double> coordinates;
  std::vector<double> velocity;     // node vector
  std::vector<double> temperature;  // cell scalar
  std::vector<int> active;
};

BodyData body_data(const BodyTopology& t, int snapshot) {
  const std::size_t dim = static_cast<std::size_t>(t.dimension);
  const double s = static_cast<double>(snapshot);
  BodyData d;
  d.coordinates = values(t.num_nodes * dim, 1.0 + s);
  d.velocity = values(t.num_nodes * dim, 2.0 + s);
  d.temperature = values(cell_count(t), 3.0 + s);
  d.active.assign(cell_count(t), 1);
  for (int e = 0; e < snapshot && e < static_cast<int>(d.active.size()); ++e) {
    d.active[static_cast<std::size_t>(e)] = 0;  // one more cell eroded per snapshot
  }
  return d;
}

BodySnapshot view(const BodyTopology& t, const BodyData& d) {
  BodySnapshot s;
  s.body = t.name;
  s.coordinates = d.coordinates;
  s.fields.push_back({"velocity", "m/s", false, t.dimension, d.velocity});
  s.fields.push_back({"temperature", "K", true, 1, d.temperature});
  s.active_cells = d.active;
  return s;
}

std::string read_text_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

struct DataItemRef {
  std::vector<std::size_t> dims;
  std::string file;
  std::string path;
};

// Every <DataItem Dimensions="..." ...>file:/path</DataItem> in the text.
std::vector<DataItemRef> data_items(const std::string& xml) {
  std::vector<DataItemRef> items;
  for (std::size_t at = xml.find("<DataItem "); at != std::string::npos;
       at = xml.find("<DataItem ", at + 1)) {
    const std::size_t tag_end = xml.find('>', at);
    const std::size_t close = xml.find("</DataItem>", tag_end);
    const std::string tag = xml.substr(at, tag_end - at);
    const std::string body = xml.substr(tag_end + 1, close - tag_end - 1);
    const std::size_t dims_at = tag.find("Dimensions=\"") + 12;
    std::istringstream dims(tag.substr(dims_at, tag.find('"', dims_at) - dims_at));
    DataItemRef ref;
    for (std::size_t d = 0; dims >> d;) ref.dims.push_back(d);
    const std::size_t colon = body.find(':');
    ref.file = body.substr(0, colon);
    ref.path = body.substr(colon + 1);
    items.push_back(ref);
  }
  return items;
}

const std::vector<std::pair<std::string, std::string>> k_columns = {
    {"time", "s"}, {"kinetic_energy", "J"}, {"contact_force", "N"}, {"adhesion_energy", "J"}};

// Three snapshots of a quad particle and a hex substrate, written on construction.
struct SnapshotRun {
  SnapshotRun() {
    ResultFile out(h5, bodies, k_columns);
    for (std::size_t k = 0; k < times.size(); ++k) {
      const int snapshot = static_cast<int>(k);
      data.push_back({body_data(bodies[0], snapshot), body_data(bodies[1], snapshot)});
      // Given in reverse order: the file orders bodies by the topology list.
      const std::vector<BodySnapshot> views = {view(bodies[1], data[k][1]),
                                               view(bodies[0], data[k][0])};
      out.write_snapshot(times[k], views);
    }
    out.close();
  }

  TempDir dir;
  fs::path h5 = dir.path() / "impact.h5";
  std::vector<BodyTopology> bodies = {quad_grid("particle", 3, 2), hex_grid("substrate", 2, 2, 1)};
  std::vector<double> times = {0.0, 1.0e-9 / 3.0, 2.5e-8};  // s
  std::vector<std::vector<BodyData>> data;                  // [snapshot][body]
};

TEST(ResultFile, attributes_round_trip) {
  TempDir dir;
  const fs::path h5 = dir.path() / "run.h5";
  {
    ResultFile out(h5, {}, {});
    out.set_attribute("solver_version", "0.1.0-test");
    out.set_attribute("outcome", "running");
    out.set_attribute("outcome", "finished");  // replaced
    out.set_attribute("reason", "reached end time; \"quotes\" & <tags>");
    out.set_attribute("impact_velocity", 612.345678901234567, "m/s");
    out.set_attribute("steps", 123456789012LL);
    out.set_attribute("seed", -7LL);
  }  // the destructor closes
  const ResultSummary s = read_result_summary(h5);
  EXPECT_EQ(s.text_attributes.at("solver_version"), "0.1.0-test");
  EXPECT_EQ(s.text_attributes.at("outcome"), "finished");
  EXPECT_EQ(s.text_attributes.at("reason"), "reached end time; \"quotes\" & <tags>");
  EXPECT_EQ(s.number_attributes.at("impact_velocity"), 612.345678901234567);
  EXPECT_EQ(s.text_attributes.at("impact_velocity_unit"), "m/s");
  EXPECT_EQ(s.number_attributes.at("steps"), 123456789012.0);
  EXPECT_EQ(s.number_attributes.at("seed"), -7.0);
  EXPECT_EQ(s.text_attributes.at("format"), "splat-result");
  EXPECT_EQ(s.number_attributes.at("format_version"), 1.0);
  EXPECT_EQ(s.text_attributes.count("steps_unit"), 0u);
  EXPECT_EQ(s.snapshots, 0u);
  EXPECT_EQ(s.history_rows, 0u);
}

TEST(ResultFile, attribute_changing_type_drops_its_unit) {
  TempDir dir;
  const fs::path h5 = dir.path() / "run.h5";
  {
    ResultFile out(h5, {}, {});
    out.set_attribute("wall_time", 12.5, "s");
    out.set_attribute("wall_time", "unknown");
  }
  const ResultSummary s = read_result_summary(h5);
  EXPECT_EQ(s.text_attributes.at("wall_time"), "unknown");
  EXPECT_EQ(s.text_attributes.count("wall_time_unit"), 0u);
  EXPECT_EQ(s.number_attributes.count("wall_time"), 0u);
}

TEST(ResultFile, history_of_ten_thousand_rows_round_trips) {
  TempDir dir;
  const fs::path h5 = dir.path() / "run.h5";
  constexpr std::size_t rows = 10000;
  std::vector<std::vector<double>> expected(k_columns.size());
  for (std::size_t c = 0; c < k_columns.size(); ++c) {
    expected[c] = values(rows, static_cast<double>(c) + 0.5);
  }
  expected[1][17] = std::numeric_limits<double>::infinity();
  expected[2][9999] = std::numeric_limits<double>::denorm_min();
  {
    ResultFile out(h5, {}, k_columns);
    for (std::size_t r = 0; r < rows; ++r) {
      const std::vector<double> row = {expected[0][r], expected[1][r], expected[2][r],
                                       expected[3][r]};
      out.append_history(row);
    }
    out.close();
    out.close();  // idempotent
  }
  const ResultSummary s = read_result_summary(h5);
  ASSERT_EQ(s.history_columns.size(), k_columns.size());
  EXPECT_EQ(s.history_rows, rows);
  for (std::size_t c = 0; c < k_columns.size(); ++c) {
    EXPECT_EQ(s.history_columns[c], k_columns[c].first);  // creation order, not alphabetical
    EXPECT_EQ(read_history(h5, k_columns[c].first), expected[c]) << k_columns[c].first;
    EXPECT_EQ(read_unit(h5, "/history/" + k_columns[c].first), k_columns[c].second);
  }
}

TEST(ResultFile, snapshot_fields_round_trip_exactly) {
  const SnapshotRun run;
  const ResultSummary s = read_result_summary(run.h5);
  EXPECT_EQ(s.snapshots, 3u);
  EXPECT_EQ(s.history_rows, 0u);
  EXPECT_EQ(s.history_columns.size(), k_columns.size());
  for (const BodyTopology& t : run.bodies) {
    EXPECT_EQ(read_connectivity(run.h5, t.name), t.connectivity) << t.name;
    const auto shape = read_dataset_shape(run.h5, "/bodies/" + t.name + "/connectivity");
    ASSERT_TRUE(shape.has_value());
    EXPECT_EQ(*shape,
              (std::vector<std::size_t>{cell_count(t), t.kind == CellKind::quad4 ? 4u : 8u}));
  }
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(read_snapshot_time(run.h5, k), run.times[k]);
    for (std::size_t b = 0; b < run.bodies.size(); ++b) {
      const std::string& name = run.bodies[b].name;
      const BodyData& d = run.data[k][b];
      EXPECT_EQ(read_snapshot_field(run.h5, k, name, "coordinates"), d.coordinates);
      EXPECT_EQ(read_snapshot_field(run.h5, k, name, "velocity"), d.velocity);
      EXPECT_EQ(read_snapshot_field(run.h5, k, name, "temperature"), d.temperature);
      const std::vector<double> active(d.active.begin(), d.active.end());
      EXPECT_EQ(read_snapshot_field(run.h5, k, name, "active"), active);
      std::vector<double> eroded;
      for (int a : d.active) eroded.push_back(1.0 - a);
      EXPECT_EQ(read_snapshot_field(run.h5, k, name, "eroded"), eroded);
      const std::string base = "/snapshots/" + std::to_string(k) + "/" + name;
      EXPECT_EQ(read_unit(run.h5, base + "/coordinates"), "m");
      EXPECT_EQ(read_unit(run.h5, base + "/velocity"), "m/s");
      EXPECT_EQ(read_unit(run.h5, base + "/temperature"), "K");
      const auto velocity_shape = read_dataset_shape(run.h5, base + "/velocity");
      ASSERT_TRUE(velocity_shape.has_value());
      EXPECT_EQ(*velocity_shape,
                (std::vector<std::size_t>{run.bodies[b].num_nodes,
                                          static_cast<std::size_t>(run.bodies[b].dimension)}));
    }
  }
  EXPECT_EQ(run.data[2][0].active[0], 0);  // the erosion really is in the data compared above
}

TEST(ResultFile, xdmf_names_every_snapshot_and_existing_datasets) {
  const SnapshotRun run;
  const fs::path xmf = run.dir.path() / "impact.xmf";
  ASSERT_TRUE(fs::exists(xmf));
  EXPECT_FALSE(fs::exists(run.dir.path() / "impact.xmf.tmp"));
  const std::string xml = read_text_file(xmf);

  // Well nested enough for an XML parser: every element that opens closes.
  EXPECT_EQ(xml.rfind("<?xml", 0), 0u);
  for (const std::string tag :
       {"Xdmf", "Domain", "Grid", "Topology", "Geometry", "Attribute", "DataItem"}) {
    EXPECT_EQ(count(xml, "<" + tag + " ") + count(xml, "<" + tag + ">"),
              count(xml, "</" + tag + ">"))
        << tag;
  }
  // One temporal collection of 3 spatial collections of 2 uniform grids.
  EXPECT_EQ(count(xml, "CollectionType=\"Temporal\""), 1u);
  EXPECT_EQ(count(xml, "CollectionType=\"Spatial\""), 3u);
  EXPECT_EQ(count(xml, "GridType=\"Uniform\""), 6u);
  EXPECT_EQ(count(xml, "<Time "), 3u);
  EXPECT_EQ(count(xml, "TopologyType=\"Quadrilateral\""), 3u);
  EXPECT_EQ(count(xml, "TopologyType=\"Hexahedron\""), 3u);
  EXPECT_EQ(count(xml, "GeometryType=\"XY\""), 3u);
  EXPECT_EQ(count(xml, "GeometryType=\"XYZ\""), 3u);
  // Names carry the unit; the eroded flag (1 - active) is what a threshold keeps out.
  EXPECT_EQ(
      count(xml, "<Attribute Name=\"velocity [m/s]\" AttributeType=\"Vector\" Center=\"Node\">"),
      6u);
  EXPECT_EQ(
      count(xml, "<Attribute Name=\"temperature [K]\" AttributeType=\"Scalar\" Center=\"Cell\">"),
      6u);
  EXPECT_EQ(count(xml, "<Attribute Name=\"eroded\" AttributeType=\"Scalar\" Center=\"Cell\">"), 6u);
  EXPECT_EQ(count(xml, "Name=\"active\""), 0u);

  // Each snapshot's times, in order.
  std::size_t at = 0;
  for (double t : run.times) {
    at = xml.find("<Time Value=\"", at);
    ASSERT_NE(at, std::string::npos);
    at += 13;
    EXPECT_EQ(std::stod(xml.substr(at, xml.find('"', at) - at)), t);
  }

  // Every DataItem points into the .h5 beside it, at a dataset of the stated shape.
  const std::vector<DataItemRef> items = data_items(xml);
  EXPECT_EQ(items.size(), 6u * 5u);  // topology, geometry, 3 attributes per grid
  for (const DataItemRef& item : items) {
    EXPECT_EQ(item.file, "impact.h5");
    const auto shape = read_dataset_shape(run.h5, item.path);
    ASSERT_TRUE(shape.has_value()) << item.path;
    EXPECT_EQ(*shape, item.dims) << item.path;
  }
  EXPECT_FALSE(read_dataset_shape(run.h5, "/snapshots/3/particle/coordinates").has_value());
  EXPECT_FALSE(read_dataset_shape(run.h5, "/snapshots/0/particle").has_value());  // a group
}

TEST(ResultFile, empty_run_is_a_valid_pair) {
  TempDir dir;
  const fs::path h5 = dir.path() / "empty.h5";
  { ResultFile out(h5, {quad_grid("particle", 1, 1)}, k_columns); }
  const ResultSummary s = read_result_summary(h5);
  EXPECT_EQ(s.snapshots, 0u);
  EXPECT_EQ(s.history_rows, 0u);
  EXPECT_EQ(s.history_columns.size(), k_columns.size());
  EXPECT_TRUE(read_history(h5, "time").empty());
  EXPECT_EQ(read_unit(h5, "/history/contact_force"), "N");
  // Nothing for ParaView to show: no .xmf (it would open with 0 points).
  EXPECT_FALSE(fs::exists(dir.path() / "empty.xmf"));
}

TEST(ResultFile, a_stale_xdmf_goes_with_the_file_it_described) {
  TempDir dir;
  const fs::path h5 = dir.path() / "again.h5";
  const std::vector<BodyTopology> bodies = {quad_grid("particle", 1, 1)};
  {
    ResultFile out(h5, bodies, k_columns);
    const BodyData d = body_data(bodies[0], 0);
    const std::vector<BodySnapshot> views = {view(bodies[0], d)};
    out.write_snapshot(0.0, views);
  }
  ASSERT_TRUE(fs::exists(dir.path() / "again.xmf"));
  { ResultFile out(h5, bodies, k_columns); }  // the same run again, without snapshots
  EXPECT_FALSE(fs::exists(dir.path() / "again.xmf"));
}

TEST(ResultFile, point_bodies_are_points_with_point_data) {
  TempDir dir;
  const fs::path h5 = dir.path() / "sph.h5";
  const BodyTopology cloud{"cloud", CellKind::point, 3, {}, 4};
  const std::vector<double> x = values(12, 1.0), v = values(12, 2.0), T = values(4, 3.0);
  const std::vector<double> sigma = values(24, 4.0);
  const std::vector<int> active = {1, 0, 1, 1};
  {
    ResultFile out(h5, {cloud}, {{"time", "s"}});
    BodySnapshot s;
    s.body = "cloud";
    s.coordinates = x;
    s.fields = {{"velocity", "m/s", false, 3, v},
                {"temperature", "K", true, 1, T},
                {"stress", "Pa", true, 6, sigma}};
    s.active_cells = active;
    const std::vector<BodySnapshot> views = {s};
    out.write_snapshot(1e-9, views);
  }
  const std::string xml = read_text_file(dir.path() / "sph.xmf");
  EXPECT_EQ(count(xml, "TopologyType=\"Polyvertex\""), 1u);
  EXPECT_EQ(count(xml, "Center=\"Cell\""), 0u);
  EXPECT_EQ(count(xml, "Center=\"Node\""), 4u);
  EXPECT_EQ(
      count(xml, "<Attribute Name=\"stress [Pa]\" AttributeType=\"Tensor6\" Center=\"Node\">"), 1u);
  EXPECT_EQ(read_snapshot_field(h5, 0, "cloud", "eroded"), (std::vector<double>{0, 1, 0, 0}));
  EXPECT_EQ(read_snapshot_field(h5, 0, "cloud", "stress"), sigma);
  for (const DataItemRef& item : data_items(xml)) {
    const auto shape = read_dataset_shape(h5, item.path);
    ASSERT_TRUE(shape.has_value()) << item.path;
    EXPECT_EQ(*shape, item.dims) << item.path;
  }
}

TEST(ResultFile, readable_when_the_run_is_cut_after_a_snapshot) {
  TempDir dir;
  const fs::path h5 = dir.path() / "run.h5";
  const std::vector<BodyTopology> bodies = {quad_grid("particle", 2, 2)};
  ResultFile out(h5, bodies, {{"time", "s"}});
  for (int r = 0; r < 1500; ++r) {  // one history flush plus a buffered tail
    const double row[] = {r * 1e-9};
    out.append_history(row);
  }
  const BodyData d = body_data(bodies[0], 0);
  const std::vector<BodySnapshot> views = {view(bodies[0], d)};
  out.write_snapshot(1.5e-6, views);
  for (int r = 0; r < 10; ++r) {  // buffered, not yet in the file
    const double row[] = {1.0};
    out.append_history(row);
  }

  // What a killed process leaves on disk: copy the pair while the writer is open.
  const fs::path cut = dir.path() / "cut";
  fs::create_directories(cut);
  fs::copy_file(h5, cut / "run.h5");
  fs::copy_file(dir.path() / "run.xmf", cut / "run.xmf");
  const ResultSummary s = read_result_summary(cut / "run.h5");
  EXPECT_EQ(s.snapshots, 1u);
  EXPECT_EQ(s.history_rows, 1500u);
  EXPECT_EQ(read_snapshot_field(cut / "run.h5", 0, "particle", "velocity"), d.velocity);
  for (const DataItemRef& item : data_items(read_text_file(cut / "run.xmf"))) {
    EXPECT_TRUE(read_dataset_shape(cut / "run.h5", item.path).has_value()) << item.path;
  }
  out.close();
  EXPECT_EQ(read_result_summary(h5).history_rows, 1510u);
}

TEST(ResultFile, unwritable_path_throws_naming_the_path) {
  TempDir dir;
  const fs::path missing_dir = dir.path() / "no_such_dir" / "run.h5";
  try {
    ResultFile out(missing_dir, {}, {});
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing_dir.string()), std::string::npos) << e.what();
  }
  // A parent that is a regular file: refused even for root.
  const fs::path plain_file = dir.path() / "plain";
  std::ofstream(plain_file) << "x";
  const fs::path under_file = plain_file / "run.h5";
  try {
    ResultFile out(under_file, {}, {});
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(under_file.string()), std::string::npos) << e.what();
  }
}

TEST(ResultFile, history_row_of_wrong_width_throws) {
  TempDir dir;
  ResultFile out(dir.path() / "run.h5", {}, k_columns);
  const std::vector<double> short_row = {1.0, 2.0};
  try {
    out.append_history(short_row);
    FAIL() << "expected an exception";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("2 values"), std::string::npos) << message;
    EXPECT_NE(message.find("4 columns"), std::string::npos) << message;
    EXPECT_NE(message.find("kinetic_energy"), std::string::npos) << message;
  }
  const std::vector<double> good_row = {1.0, 2.0, 3.0, 4.0};
  out.append_history(good_row);
  out.close();
  EXPECT_EQ(read_result_summary(dir.path() / "run.h5").history_rows, 1u);
}

TEST(ResultFile, rejected_snapshot_leaves_no_trace) {
  TempDir dir;
  const fs::path h5 = dir.path() / "run.h5";
  const std::vector<BodyTopology> bodies = {quad_grid("particle", 2, 1)};
  ResultFile out(h5, bodies, {});
  BodyData d = body_data(bodies[0], 0);
  BodySnapshot bad = view(bodies[0], d);
  bad.fields[1].values = bad.fields[1].values.first(1);  // one temperature for two cells
  EXPECT_THROW(out.write_snapshot(0.0, std::span(&bad, 1)), std::invalid_argument);
  BodySnapshot unknown = view(bodies[0], d);
  unknown.body = "substrate";
  EXPECT_THROW(out.write_snapshot(0.0, std::span(&unknown, 1)), std::invalid_argument);
  EXPECT_THROW(out.write_snapshot(0.0, {}), std::invalid_argument);  // a body missing
  const BodySnapshot good = view(bodies[0], d);
  out.write_snapshot(0.0, std::span(&good, 1));
  EXPECT_THROW(out.write_snapshot(-1.0, std::span(&good, 1)), std::invalid_argument);
  out.close();
  EXPECT_THROW(out.write_snapshot(1.0, std::span(&good, 1)), std::logic_error);
  EXPECT_EQ(read_result_summary(h5).snapshots, 1u);
}

TEST(ResultFile, reading_what_is_not_there_names_the_path) {
  TempDir dir;
  const fs::path h5 = dir.path() / "run.h5";
  { ResultFile out(h5, {}, {{"time", "s"}}); }
  try {
    read_history(h5, "pressure");
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/history/pressure"), std::string::npos) << e.what();
  }
  try {
    read_result_summary(dir.path() / "absent.h5");
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("absent.h5"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace splat
