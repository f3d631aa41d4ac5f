// HDF5 and XDMF writing and reading of result files (layout in result_file.hpp).
// The HDF5 C API is used only here; every hid_t lives in a Handle.
#include "solver/io/result_file.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <limits>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <system_error>

namespace splat {
namespace {

constexpr int k_format_version = 1;
constexpr const char* k_format_name = "splat-result";

// Serialises this module's HDF5 calls (a non-thread-safe HDF5 build must not be
// entered concurrently) and silences HDF5's automatic error printing for the
// duration of one call into this module; errors become exceptions instead.
class Hdf5Scope {
 public:
  Hdf5Scope() : lock_(mutex()) {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~Hdf5Scope() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  Hdf5Scope(const Hdf5Scope&) = delete;
  Hdf5Scope& operator=(const Hdf5Scope&) = delete;

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  std::lock_guard<std::mutex> lock_;
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

herr_t innermost_error(unsigned n, const H5E_error2_t* err, void* data) noexcept {
  // Walked upward, entry 0 is where the error was detected: the most specific.
  if (n == 0 && err != nullptr && err->desc != nullptr) {
    try {
      *static_cast<std::string*>(data) = err->desc;
    } catch (...) {
      return -1;
    }
  }
  return 0;
}

std::string take_hdf5_error() {
  std::string text;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, innermost_error, &text);
  H5Eclear2(H5E_DEFAULT);
  return text.empty() ? std::string("no detail from HDF5") : text;
}

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& what) {
  throw ResultFileError("result file '" + file.string() + "': " + what + " (" + take_hdf5_error() +
                        ")");
}

void check(herr_t status, const std::filesystem::path& file, const std::string& what) {
  if (status < 0) fail(file, what);
}

using Closer = herr_t (*)(hid_t);

// Owns one HDF5 identifier and closes it with the matching H5?close.
class Handle {
 public:
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  ~Handle() { reset(); }
  Handle(Handle&& other) noexcept : id_(other.id_), closer_(other.closer_) {
    other.id_ = H5I_INVALID_HID;
  }
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
      closer_ = other.closer_;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  hid_t get() const { return id_; }
  // Closes now and returns the status (a file's close flushes and can fail).
  herr_t close() noexcept {
    if (id_ < 0) return 0;
    const herr_t status = closer_(std::exchange(id_, H5I_INVALID_HID));
    return status;
  }
  void reset() noexcept { static_cast<void>(close()); }

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

Handle checked(hid_t id, Closer closer, const std::filesystem::path& file,
               const std::string& what) {
  if (id < 0) fail(file, what);
  return Handle(id, closer);
}

std::string in_quotes(const std::string& s) {
  return "'" + s + "'";
}

Handle create_group(hid_t parent, const std::string& name, const std::filesystem::path& file,
                    const std::string& full_path) {
  Handle gcpl = checked(H5Pcreate(H5P_GROUP_CREATE), H5Pclose, file, "cannot create property list");
  check(H5Pset_link_creation_order(gcpl.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED), file,
        "cannot track creation order for " + in_quotes(full_path));
  return checked(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT), H5Gclose,
                 file, "cannot create group " + in_quotes(full_path));
}

void delete_attribute_if_present(hid_t obj, const std::string& name,
                                 const std::filesystem::path& file, const std::string& obj_path) {
  const htri_t exists = H5Aexists(obj, name.c_str());
  if (exists < 0)
    fail(file, "cannot query attribute " + in_quotes(name) + " on " + in_quotes(obj_path));
  if (exists > 0) {
    check(H5Adelete(obj, name.c_str()), file,
          "cannot replace attribute " + in_quotes(name) + " on " + in_quotes(obj_path));
  }
}

Handle utf8_string_type(const std::filesystem::path& file) {
  Handle type = checked(H5Tcopy(H5T_C_S1), H5Tclose, file, "cannot create string type");
  check(H5Tset_size(type.get(), H5T_VARIABLE), file, "cannot create string type");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), file, "cannot create string type");
  return type;
}

// Variable-length UTF-8 string attribute (read as str by h5py).
void write_text_attribute(hid_t obj, const std::string& name, const std::string& value,
                          const std::filesystem::path& file, const std::string& obj_path) {
  delete_attribute_if_present(obj, name, file, obj_path);
  const std::string what =
      "cannot write attribute " + in_quotes(name) + " on " + in_quotes(obj_path);
  Handle type = utf8_string_type(file);
  Handle space = checked(H5Screate(H5S_SCALAR), H5Sclose, file, what);
  Handle attr =
      checked(H5Acreate2(obj, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
              H5Aclose, file, what);
  const char* text = value.c_str();
  check(H5Awrite(attr.get(), type.get(), &text), file, what);
}

void write_scalar_attribute(hid_t obj, const std::string& name, hid_t file_type, hid_t mem_type,
                            const void* value, const std::filesystem::path& file,
                            const std::string& obj_path) {
  delete_attribute_if_present(obj, name, file, obj_path);
  const std::string what =
      "cannot write attribute " + in_quotes(name) + " on " + in_quotes(obj_path);
  Handle space = checked(H5Screate(H5S_SCALAR), H5Sclose, file, what);
  Handle attr =
      checked(H5Acreate2(obj, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
              H5Aclose, file, what);
  check(H5Awrite(attr.get(), mem_type, value), file, what);
}

void write_double_attribute(hid_t obj, const std::string& name, double value,
                            const std::filesystem::path& file, const std::string& obj_path) {
  write_scalar_attribute(obj, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value, file, obj_path);
}

void write_integer_attribute(hid_t obj, const std::string& name, long long value,
                             const std::filesystem::path& file, const std::string& obj_path) {
  write_scalar_attribute(obj, name, H5T_STD_I64LE, H5T_NATIVE_LLONG, &value, file, obj_path);
}

// A contiguous dataset written in one go; returned open for attributes.
Handle write_dataset(hid_t parent, const std::string& name, const std::vector<hsize_t>& dims,
                     hid_t file_type, hid_t mem_type, const void* data,
                     const std::filesystem::path& file, const std::string& full_path) {
  const std::string what = "cannot write dataset " + in_quotes(full_path);
  Handle space = checked(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                         H5Sclose, file, what);
  Handle dataset = checked(H5Dcreate2(parent, name.c_str(), file_type, space.get(), H5P_DEFAULT,
                                      H5P_DEFAULT, H5P_DEFAULT),
                           H5Dclose, file, what);
  hsize_t count = 1;
  for (hsize_t d : dims) count *= d;
  if (count > 0) {
    check(H5Dwrite(dataset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), file, what);
  }
  return dataset;
}

Handle open_file_read_only(const std::filesystem::path& file) {
  return checked(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, file,
                 "cannot open for reading");
}

Handle open_object(hid_t loc, const std::string& path, const std::filesystem::path& file) {
  return checked(H5Oopen(loc, path.c_str(), H5P_DEFAULT), H5Oclose, file,
                 "no object " + in_quotes(path));
}

Handle open_attribute(hid_t obj, const std::string& name, const std::filesystem::path& file,
                      const std::string& obj_path) {
  const htri_t exists = H5Aexists(obj, name.c_str());
  if (exists < 0)
    fail(file, "cannot query attribute " + in_quotes(name) + " on " + in_quotes(obj_path));
  if (exists == 0) {
    throw std::runtime_error("result file '" + file.string() + "': no attribute " +
                             in_quotes(name) + " on " + in_quotes(obj_path));
  }
  return checked(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose, file,
                 "cannot open attribute " + in_quotes(name) + " on " + in_quotes(obj_path));
}

std::size_t attribute_points(hid_t attr, const std::filesystem::path& file,
                             const std::string& what) {
  Handle space = checked(H5Aget_space(attr), H5Sclose, file, what);
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  if (n < 0) fail(file, what);
  return static_cast<std::size_t>(n);
}

// Reads a one-element string attribute, variable or fixed length.
std::string read_text(hid_t attr, const std::filesystem::path& file, const std::string& what) {
  if (attribute_points(attr, file, what) != 1) {
    throw std::runtime_error("result file '" + file.string() + "': " + what +
                             ": not a single string");
  }
  Handle file_type = checked(H5Aget_type(attr), H5Tclose, file, what);
  const htri_t variable = H5Tis_variable_str(file_type.get());
  if (variable < 0) fail(file, what);
  Handle mem_type = checked(H5Tcopy(H5T_C_S1), H5Tclose, file, what);
  check(H5Tset_cset(mem_type.get(), H5Tget_cset(file_type.get())), file, what);
  if (variable > 0) {
    check(H5Tset_size(mem_type.get(), H5T_VARIABLE), file, what);
    char* text = nullptr;
    check(H5Aread(attr, mem_type.get(), &text), file, what);
    std::string value = text != nullptr ? std::string(text) : std::string();
    H5free_memory(text);
    return value;
  }
  // Fixed length: one extra byte so a string that fills its width keeps its last character.
  const std::size_t size = H5Tget_size(file_type.get());
  if (size == 0) fail(file, what);
  check(H5Tset_size(mem_type.get(), size + 1), file, what);
  check(H5Tset_strpad(mem_type.get(), H5T_STR_NULLTERM), file, what);
  std::vector<char> buffer(size + 1, '\0');
  check(H5Aread(attr, mem_type.get(), buffer.data()), file, what);
  return std::string(buffer.data());
}

double read_number(hid_t attr, const std::filesystem::path& file, const std::string& what) {
  if (attribute_points(attr, file, what) != 1) {
    throw std::runtime_error("result file '" + file.string() + "': " + what +
                             ": not a single number");
  }
  double value = 0.0;
  check(H5Aread(attr, H5T_NATIVE_DOUBLE, &value), file, what);
  return value;
}

std::string read_text_attribute(hid_t obj, const std::string& name,
                                const std::filesystem::path& file, const std::string& obj_path) {
  Handle attr = open_attribute(obj, name, file, obj_path);
  return read_text(attr.get(), file,
                   "cannot read attribute " + in_quotes(name) + " on " + in_quotes(obj_path));
}

double read_number_attribute(hid_t obj, const std::string& name, const std::filesystem::path& file,
                             const std::string& obj_path) {
  Handle attr = open_attribute(obj, name, file, obj_path);
  return read_number(attr.get(), file,
                     "cannot read attribute " + in_quotes(name) + " on " + in_quotes(obj_path));
}

std::vector<hsize_t> dataset_dims(hid_t dataset, const std::filesystem::path& file,
                                  const std::string& path) {
  const std::string what = "cannot read the shape of " + in_quotes(path);
  Handle space = checked(H5Dget_space(dataset), H5Sclose, file, what);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) fail(file, what);
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  if (rank > 0 && H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr) < 0) {
    fail(file, what);
  }
  return dims;
}

template <typename T>
std::vector<T> read_dataset_values(hid_t loc, const std::string& path, hid_t mem_type,
                                   const std::filesystem::path& file) {
  Handle dataset = checked(H5Dopen2(loc, path.c_str(), H5P_DEFAULT), H5Dclose, file,
                           "no dataset " + in_quotes(path));
  std::size_t count = 1;
  for (hsize_t d : dataset_dims(dataset.get(), file, path)) count *= static_cast<std::size_t>(d);
  std::vector<T> values(count);
  if (count > 0) {
    check(H5Dread(dataset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), file,
          "cannot read dataset " + in_quotes(path));
  }
  return values;
}

// Link names of a group, in creation order where the group tracks it.
std::vector<std::string> link_names(hid_t group, const std::filesystem::path& file,
                                    const std::string& path) {
  const std::string what = "cannot list group " + in_quotes(path);
  H5G_info_t info;
  check(H5Gget_info(group, &info), file, what);
  Handle gcpl = checked(H5Gget_create_plist(group), H5Pclose, file, what);
  unsigned order_flags = 0;
  check(H5Pget_link_creation_order(gcpl.get(), &order_flags), file, what);
  const H5_index_t index =
      (order_flags & H5P_CRT_ORDER_TRACKED) != 0 ? H5_INDEX_CRT_ORDER : H5_INDEX_NAME;
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t length =
        H5Lget_name_by_idx(group, ".", index, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (length < 0) fail(file, what);
    std::vector<char> buffer(static_cast<std::size_t>(length) + 1, '\0');
    if (H5Lget_name_by_idx(group, ".", index, H5_ITER_INC, i, buffer.data(), buffer.size(),
                           H5P_DEFAULT) < 0) {
      fail(file, what);
    }
    names.emplace_back(buffer.data());
  }
  return names;
}

herr_t collect_attribute_name(hid_t, const char* name, const H5A_info_t*, void* data) noexcept {
  try {
    static_cast<std::vector<std::string>*>(data)->emplace_back(name);
  } catch (...) {
    return -1;
  }
  return 0;
}

// True if every component of path exists and resolves to an object
// (H5Lexists on each prefix, then H5Oexists_by_name for dangling links).
bool object_exists(hid_t file_id, const std::string& path, const std::filesystem::path& file) {
  if (path.empty() || path.front() != '/') return false;
  std::string prefix;
  std::size_t start = 1;
  while (start <= path.size()) {
    std::size_t end = path.find('/', start);
    if (end == std::string::npos) end = path.size();
    if (end > start) {
      prefix.push_back('/');
      prefix.append(path, start, end - start);
      const htri_t link = H5Lexists(file_id, prefix.c_str(), H5P_DEFAULT);
      if (link < 0) fail(file, "cannot look up " + in_quotes(prefix));
      if (link == 0) return false;
      const htri_t object = H5Oexists_by_name(file_id, prefix.c_str(), H5P_DEFAULT);
      if (object < 0) fail(file, "cannot look up " + in_quotes(prefix));
      if (object == 0) return false;
    }
    start = end + 1;
  }
  return true;
}

// Names become HDF5 path components and XML attribute values: keep them plain.
bool is_plain_name(const std::string& s) {
  if (s.empty() || s == "." || s == "..") return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '.' || c == '+' || c == '-';
  });
}

void require_plain_name(const std::string& name, const std::string& kind) {
  if (!is_plain_name(name)) {
    throw std::invalid_argument("result file: " + kind + " name " + in_quotes(name) +
                                " must be non-empty and use only letters, digits and _ . + -");
  }
}

std::size_t nodes_per_cell(CellKind kind) {
  switch (kind) {
    case CellKind::quad4:
      return 4;
    case CellKind::hex8:
      return 8;
    case CellKind::point:
      return 1;
  }
  return 1;
}

const char* cell_kind_name(CellKind kind) {
  switch (kind) {
    case CellKind::quad4:
      return "quad4";
    case CellKind::hex8:
      return "hex8";
    case CellKind::point:
      return "point";
  }
  return "?";
}

const char* xdmf_topology_name(CellKind kind) {
  switch (kind) {
    case CellKind::quad4:
      return "Quadrilateral";
    case CellKind::hex8:
      return "Hexahedron";
    case CellKind::point:
      return "Polyvertex";
  }
  return "?";
}

const char* xdmf_attribute_type(int components) {
  switch (components) {
    case 1:
      return "Scalar";
    case 2:
    case 3:
      return "Vector";
    case 6:
      return "Tensor6";
    case 9:
      return "Tensor";
    default:
      return "Matrix";
  }
}

bool supported_components(int c) {
  return c == 1 || c == 2 || c == 3 || c == 6 || c == 9;
}

// Checks a body and returns its number of cells.
std::size_t validate_body(const BodyTopology& body) {
  require_plain_name(body.name, "body");
  const std::string where = "result file: body " + in_quotes(body.name) + ": ";
  if (body.kind == CellKind::quad4 && body.dimension != 2) {
    throw std::invalid_argument(where + "quad4 cells need dimension 2");
  }
  if (body.kind == CellKind::hex8 && body.dimension != 3) {
    throw std::invalid_argument(where + "hex8 cells need dimension 3");
  }
  if (body.dimension != 2 && body.dimension != 3) {
    throw std::invalid_argument(where + "dimension must be 2 or 3");
  }
  if (body.num_nodes == 0) throw std::invalid_argument(where + "has no nodes");
  if (body.num_nodes > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw std::invalid_argument(where + "too many nodes for int32 connectivity");
  }
  if (body.kind == CellKind::point) {
    if (!body.connectivity.empty()) {
      throw std::invalid_argument(where + "point bodies take no connectivity");
    }
    return body.num_nodes;
  }
  const std::size_t npc = nodes_per_cell(body.kind);
  if (body.connectivity.empty() || body.connectivity.size() % npc != 0) {
    throw std::invalid_argument(where + "connectivity length " +
                                std::to_string(body.connectivity.size()) +
                                " is not a positive multiple of " + std::to_string(npc));
  }
  const int num_nodes = static_cast<int>(body.num_nodes);
  for (int node : body.connectivity) {
    if (node < 0 || node >= num_nodes) {
      throw std::invalid_argument(where + "connectivity refers to node " + std::to_string(node) +
                                  " of " + std::to_string(num_nodes));
    }
  }
  return body.connectivity.size() / npc;
}

std::string xml_escape(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// Shortest text that reads back to the same double.
std::string exact_text(double v) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), v);
  return std::string(buffer, result.ptr);
}

// The name ParaView and meshio show: the dataset's name with its unit in
// brackets ("temperature [K]"); dimensionless fields keep the bare name.
std::string display_name(const std::string& name, const std::string& unit) {
  if (unit.empty() || unit == "-" || unit == "1") return name;
  return name + " [" + unit + "]";
}

struct XdmfField {
  std::string name;          // dataset name under the snapshot's body group
  std::string display_name;  // XDMF Attribute Name
  bool on_cells = false;     // Center="Cell" (point bodies: always node-centred)
  int components = 1;
  bool is_integer = false;
};

struct XdmfSnapshot {
  double time = 0.0;                                // s
  std::vector<std::vector<XdmfField>> body_fields;  // per body, in topology order
};

}  // namespace

struct ResultFile::Impl {
  std::filesystem::path h5_path;
  std::filesystem::path xmf_path;
  std::vector<BodyTopology> bodies;
  std::vector<std::size_t> num_cells;  // per body
  std::vector<std::pair<std::string, std::string>> columns;

  // Declared before the other handles so that it is closed after them.
  Handle file;
  Handle snapshots_group;
  std::vector<Handle> history_datasets;  // one per column

  std::vector<double> pending_history;  // row-major rows not yet in the file
  hsize_t history_rows_written = 0;
  std::vector<XdmfSnapshot> snapshots;
  bool closed = false;

  void flush_file() { check(H5Fflush(file.get(), H5F_SCOPE_LOCAL), h5_path, "cannot flush"); }

  // Extends every column by the pending rows and writes them.
  void write_pending_history() {
    if (columns.empty() || pending_history.empty()) return;
    const std::size_t width = columns.size();
    const std::size_t rows = pending_history.size() / width;
    const hsize_t start = history_rows_written;
    const hsize_t count = rows;
    const hsize_t new_size = start + count;
    std::vector<double> column_values(rows);
    for (std::size_t c = 0; c < width; ++c) {
      const std::string path = "/history/" + columns[c].first;
      const std::string what = "cannot append to " + in_quotes(path);
      for (std::size_t r = 0; r < rows; ++r) column_values[r] = pending_history[r * width + c];
      const hid_t dataset = history_datasets[c].get();
      check(H5Dset_extent(dataset, &new_size), h5_path, what);
      Handle file_space = checked(H5Dget_space(dataset), H5Sclose, h5_path, what);
      check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, &start, nullptr, &count, nullptr),
            h5_path, what);
      Handle mem_space = checked(H5Screate_simple(1, &count, nullptr), H5Sclose, h5_path, what);
      check(H5Dwrite(dataset, H5T_NATIVE_DOUBLE, mem_space.get(), file_space.get(), H5P_DEFAULT,
                     column_values.data()),
            h5_path, what);
    }
    history_rows_written = new_size;
    pending_history.clear();
  }

  // Writes the .xmf once there is a snapshot to show (an .xmf without one
  // opens as an empty data set).
  void write_xmf() const {
    if (snapshots.empty()) return;
    const std::string h5_name = xml_escape(h5_path.filename().string());
    std::ostringstream out;
    out << "<?xml version=\"1.0\" ?>\n"
        << "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
        << "<Xdmf Version=\"3.0\">\n"
        << "  <Domain>\n"
        << "    <Grid Name=\"run\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    auto data_item = [&](const std::string& indent, const std::string& dims, bool is_integer,
                         const std::string& path) {
      out << indent << "<DataItem Dimensions=\"" << dims << "\" NumberType=\""
          << (is_integer ? "Int\" Precision=\"4\"" : "Float\" Precision=\"8\"")
          << " Format=\"HDF\">" << h5_name << ":" << path << "</DataItem>\n";
    };
    for (std::size_t k = 0; k < snapshots.size(); ++k) {
      const XdmfSnapshot& snapshot = snapshots[k];
      const std::string snapshot_path = "/snapshots/" + std::to_string(k);
      out << "      <Grid Name=\"snapshot_" << k
          << "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
          << "        <Time Value=\"" << exact_text(snapshot.time) << "\"/>\n";
      for (std::size_t b = 0; b < bodies.size(); ++b) {
        const BodyTopology& body = bodies[b];
        const std::string cells = std::to_string(num_cells[b]);
        const std::string nodes = std::to_string(body.num_nodes);
        const std::string body_path = snapshot_path + "/" + body.name;
        out << "        <Grid Name=\"" << xml_escape(body.name) << "\" GridType=\"Uniform\">\n"
            << "          <Topology TopologyType=\"" << xdmf_topology_name(body.kind)
            << "\" NumberOfElements=\"" << cells << "\""
            << (body.kind == CellKind::point ? " NodesPerElement=\"1\"" : "") << ">\n";
        data_item("            ", cells + " " + std::to_string(nodes_per_cell(body.kind)), true,
                  "/bodies/" + body.name + "/connectivity");
        out << "          </Topology>\n"
            << "          <Geometry GeometryType=\"" << (body.dimension == 2 ? "XY" : "XYZ")
            << "\">\n";
        data_item("            ", nodes + " " + std::to_string(body.dimension), false,
                  body_path + "/coordinates");
        out << "          </Geometry>\n";
        for (const XdmfField& field : snapshot.body_fields[b]) {
          const std::string& items = field.on_cells ? cells : nodes;
          out << "          <Attribute Name=\"" << xml_escape(field.display_name)
              << "\" AttributeType=\"" << xdmf_attribute_type(field.components) << "\" Center=\""
              << (field.on_cells ? "Cell" : "Node") << "\">\n";
          data_item("            ",
                    field.components == 1 ? items : items + " " + std::to_string(field.components),
                    field.is_integer, body_path + "/" + field.name);
          out << "          </Attribute>\n";
        }
        out << "        </Grid>\n";
      }
      out << "      </Grid>\n";
    }
    out << "    </Grid>\n  </Domain>\n</Xdmf>\n";

    // Replace atomically so a reader or a cut process never sees half a file.
    std::filesystem::path temp = xmf_path;
    temp += ".tmp";
    {
      std::ofstream stream(temp, std::ios::binary | std::ios::trunc);
      stream << out.str();
      stream.close();
      if (!stream) {
        throw ResultFileError("result file: cannot write '" + temp.string() +
                              "': " + std::generic_category().message(errno));
      }
    }
    std::error_code error;
    std::filesystem::rename(temp, xmf_path, error);
    if (error) {
      throw ResultFileError("result file: cannot rename '" + temp.string() + "' to '" +
                            xmf_path.string() + "': " + error.message());
    }
  }

  // Each body's snapshot in `given`, by body order; throws on an unknown
  // body or one given twice.
  std::vector<const BodySnapshot*> snapshots_by_body(std::span<const BodySnapshot> given,
                                                     const std::string& where) const {
    std::vector<const BodySnapshot*> by_body(bodies.size(), nullptr);
    for (const BodySnapshot& snapshot : given) {
      const auto it = std::find_if(bodies.begin(), bodies.end(),
                                   [&](const BodyTopology& b) { return b.name == snapshot.body; });
      if (it == bodies.end()) {
        throw std::invalid_argument(where + "unknown body " + in_quotes(snapshot.body));
      }
      const std::size_t b = static_cast<std::size_t>(it - bodies.begin());
      if (by_body[b] != nullptr) {
        throw std::invalid_argument(where + "body " + in_quotes(snapshot.body) + " given twice");
      }
      by_body[b] = &snapshot;
    }
    return by_body;
  }

  // Throws unless `snapshot` (null: missing) fits body b's topology.
  void check_body_snapshot(std::size_t b, const BodySnapshot* snapshot,
                           const std::string& where) const {
    const BodyTopology& body = bodies[b];
    const std::string at = where + "body " + in_quotes(body.name) + ": ";
    if (snapshot == nullptr) throw std::invalid_argument(at + "missing");
    const std::size_t dim = static_cast<std::size_t>(body.dimension);
    if (snapshot->coordinates.size() != body.num_nodes * dim) {
      throw std::invalid_argument(at + "coordinates have " +
                                  std::to_string(snapshot->coordinates.size()) +
                                  " values, expected " + std::to_string(body.num_nodes * dim));
    }
    std::set<std::string> names;
    for (const FieldView& field : snapshot->fields) {
      require_plain_name(field.name, "field");
      if (field.name == "coordinates" || field.name == "active" || field.name == "eroded") {
        throw std::invalid_argument(at + "field name " + in_quotes(field.name) + " is reserved");
      }
      if (!names.insert(field.name).second) {
        throw std::invalid_argument(at + "field " + in_quotes(field.name) + " given twice");
      }
      if (!supported_components(field.components)) {
        throw std::invalid_argument(at + "field " + in_quotes(field.name) + " has " +
                                    std::to_string(field.components) +
                                    " components; 1, 2, 3, 6 or 9 are supported");
      }
      const std::size_t items = field.on_cells ? num_cells[b] : body.num_nodes;
      const std::size_t expected = items * static_cast<std::size_t>(field.components);
      if (field.values.size() != expected) {
        throw std::invalid_argument(at + "field " + in_quotes(field.name) + " has " +
                                    std::to_string(field.values.size()) + " values, expected " +
                                    std::to_string(expected));
      }
    }
    if (!snapshot->active_cells.empty()) {
      if (snapshot->active_cells.size() != num_cells[b]) {
        throw std::invalid_argument(
            at + "active has " + std::to_string(snapshot->active_cells.size()) +
            " values, expected one per cell (" + std::to_string(num_cells[b]) + ")");
      }
      for (int a : snapshot->active_cells) {
        if (a != 0 && a != 1) throw std::invalid_argument(at + "active values must be 0 or 1");
      }
    }
  }

  // Writes body b's coordinates and fields under `group` (path
  // snapshot_path) and returns the fields the .xmf names.
  std::vector<XdmfField> write_body_snapshot(hid_t group, const std::string& snapshot_path,
                                             std::size_t b, const BodySnapshot& snapshot) const {
    const BodyTopology& body = bodies[b];
    const std::string body_path = snapshot_path + "/" + body.name;
    Handle body_group = create_group(group, body.name, h5_path, body_path);
    {
      const std::string path = body_path + "/coordinates";
      Handle dataset = write_dataset(
          body_group.get(), "coordinates", {body.num_nodes, static_cast<hsize_t>(body.dimension)},
          H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, snapshot.coordinates.data(), h5_path, path);
      write_text_attribute(dataset.get(), "unit", "m", h5_path, path);
    }
    // A point body's cells are its nodes: its fields are point data.
    const bool points = body.kind == CellKind::point;
    std::vector<XdmfField> fields;
    for (const FieldView& field : snapshot.fields) {
      const std::string path = body_path + "/" + field.name;
      const hsize_t items = field.on_cells ? num_cells[b] : body.num_nodes;
      const bool on_cells = field.on_cells && !points;
      std::vector<hsize_t> dims{items};
      if (field.components > 1) dims.push_back(static_cast<hsize_t>(field.components));
      Handle dataset = write_dataset(body_group.get(), field.name, dims, H5T_IEEE_F64LE,
                                     H5T_NATIVE_DOUBLE, field.values.data(), h5_path, path);
      write_text_attribute(dataset.get(), "unit", field.unit, h5_path, path);
      write_text_attribute(dataset.get(), "center", on_cells ? "cell" : "node", h5_path, path);
      fields.push_back(
          {field.name, display_name(field.name, field.unit), on_cells, field.components, false});
    }
    if (!snapshot.active_cells.empty()) {
      // "active" for readers of the HDF5 file; its complement "eroded" for a
      // threshold in ParaView (keep eroded < 0.5), which the .xmf names.
      std::vector<int> eroded(snapshot.active_cells.size());
      for (std::size_t c = 0; c < eroded.size(); ++c) eroded[c] = 1 - snapshot.active_cells[c];
      const char* center = points ? "node" : "cell";
      for (const auto& [name, values] :
           {std::pair<const char*, const int*>{"active", snapshot.active_cells.data()},
            std::pair<const char*, const int*>{"eroded", eroded.data()}}) {
        const std::string path = body_path + "/" + name;
        Handle dataset = write_dataset(body_group.get(), name, {num_cells[b]}, H5T_STD_I32LE,
                                       H5T_NATIVE_INT, values, h5_path, path);
        write_text_attribute(dataset.get(), "unit", "1", h5_path, path);
        write_text_attribute(dataset.get(), "center", center, h5_path, path);
      }
      fields.push_back({"eroded", "eroded", !points, 1, true});
    }
    return fields;
  }

  void require_open() const {
    if (closed) {
      throw std::logic_error("result file '" + h5_path.string() + "' is already closed");
    }
  }
};

std::filesystem::path xmf_path_for(const std::filesystem::path& h5_path) {
  std::filesystem::path xmf = h5_path;
  xmf.replace_extension(".xmf");
  return xmf;
}

ResultFile::ResultFile(const std::filesystem::path& h5_path, std::vector<BodyTopology> bodies,
                       std::vector<std::pair<std::string, std::string>> history_columns) {
  auto impl = std::make_unique<Impl>();
  impl->h5_path = h5_path;
  impl->xmf_path = xmf_path_for(h5_path);
  if (impl->xmf_path == h5_path) {
    throw std::invalid_argument("result file '" + h5_path.string() +
                                "': the HDF5 file must not end in .xmf");
  }
  std::set<std::string> seen;
  for (const BodyTopology& body : bodies) {
    impl->num_cells.push_back(validate_body(body));
    if (!seen.insert(body.name).second) {
      throw std::invalid_argument("result file: body " + in_quotes(body.name) + " given twice");
    }
  }
  seen.clear();
  for (const auto& column : history_columns) {
    require_plain_name(column.first, "history column");
    if (!seen.insert(column.first).second) {
      throw std::invalid_argument("result file: history column " + in_quotes(column.first) +
                                  " given twice");
    }
  }
  impl->bodies = std::move(bodies);
  impl->columns = std::move(history_columns);

  const Hdf5Scope scope;
  // Declared after the scope: on an exception its handles close inside it.
  std::unique_ptr<Impl> building = std::move(impl);
  Impl& m = *building;
  const std::filesystem::path& file = m.h5_path;
  m.file = checked(H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose, file,
                   "cannot create");
  const hid_t root = m.file.get();
  write_text_attribute(root, "format", k_format_name, file, "/");
  write_integer_attribute(root, "format_version", k_format_version, file, "/");

  Handle bodies_group = create_group(root, "bodies", file, "/bodies");
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const BodyTopology& body = m.bodies[b];
    const std::string body_path = "/bodies/" + body.name;
    Handle group = create_group(bodies_group.get(), body.name, file, body_path);
    std::vector<int> trivial;
    if (body.kind == CellKind::point) {
      trivial.resize(body.num_nodes);
      for (std::size_t i = 0; i < trivial.size(); ++i) trivial[i] = static_cast<int>(i);
    }
    const std::vector<int>& connectivity =
        body.kind == CellKind::point ? trivial : body.connectivity;
    const std::string path = body_path + "/connectivity";
    Handle dataset =
        write_dataset(group.get(), "connectivity", {m.num_cells[b], nodes_per_cell(body.kind)},
                      H5T_STD_I32LE, H5T_NATIVE_INT, connectivity.data(), file, path);
    write_text_attribute(dataset.get(), "cell_kind", cell_kind_name(body.kind), file, path);
    write_integer_attribute(dataset.get(), "dimension", body.dimension, file, path);
    write_integer_attribute(dataset.get(), "num_nodes", static_cast<long long>(body.num_nodes),
                            file, path);
  }

  Handle history_group = create_group(root, "history", file, "/history");
  for (const auto& [name, unit] : m.columns) {
    const std::string path = "/history/" + name;
    const std::string what = "cannot create dataset " + in_quotes(path);
    const hsize_t initial = 0;
    const hsize_t unlimited = H5S_UNLIMITED;
    const hsize_t chunk = k_history_flush_rows;
    Handle space = checked(H5Screate_simple(1, &initial, &unlimited), H5Sclose, file, what);
    Handle dcpl = checked(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, file, what);
    check(H5Pset_chunk(dcpl.get(), 1, &chunk), file, what);
    Handle dataset = checked(H5Dcreate2(history_group.get(), name.c_str(), H5T_IEEE_F64LE,
                                        space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                             H5Dclose, file, what);
    write_text_attribute(dataset.get(), "unit", unit, file, path);
    m.history_datasets.push_back(std::move(dataset));
  }

  m.snapshots_group = create_group(root, "snapshots", file, "/snapshots");
  m.flush_file();
  // An .xmf of an earlier run here would describe datasets this file no longer has.
  std::error_code ignored;
  std::filesystem::remove(m.xmf_path, ignored);
  impl_ = std::move(building);
}

ResultFile::ResultFile(ResultFile&&) noexcept = default;

ResultFile& ResultFile::operator=(ResultFile&& other) noexcept {
  if (this != &other) {
    ResultFile previous(std::move(*this));  // closes the current file on scope exit
    impl_ = std::move(other.impl_);
  }
  return *this;
}

ResultFile::~ResultFile() {
  if (!impl_) return;
  try {
    close();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "splat: closing result file failed: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "splat: closing result file failed\n");
  }
}

const std::filesystem::path& ResultFile::h5_path() const {
  if (!impl_) throw std::logic_error("result file: used after move");
  return impl_->h5_path;
}

const std::filesystem::path& ResultFile::xmf_path() const {
  if (!impl_) throw std::logic_error("result file: used after move");
  return impl_->xmf_path;
}

void ResultFile::set_attribute(const std::string& name, const std::string& value) {
  if (!impl_) throw std::logic_error("result file: used after move");
  impl_->require_open();
  if (name.empty() || name == "format" || name == "format_version") {
    throw std::invalid_argument("result file: attribute name " + in_quotes(name) +
                                " is empty or reserved");
  }
  const Hdf5Scope scope;
  write_text_attribute(impl_->file.get(), name, value, impl_->h5_path, "/");
  delete_attribute_if_present(impl_->file.get(), name + "_unit", impl_->h5_path, "/");
  impl_->flush_file();
}

void ResultFile::set_attribute(const std::string& name, double value, const std::string& unit) {
  if (!impl_) throw std::logic_error("result file: used after move");
  impl_->require_open();
  if (name.empty() || name == "format" || name == "format_version") {
    throw std::invalid_argument("result file: attribute name " + in_quotes(name) +
                                " is empty or reserved");
  }
  const Hdf5Scope scope;
  write_double_attribute(impl_->file.get(), name, value, impl_->h5_path, "/");
  write_text_attribute(impl_->file.get(), name + "_unit", unit, impl_->h5_path, "/");
  impl_->flush_file();
}

void ResultFile::set_attribute(const std::string& name, long long value) {
  if (!impl_) throw std::logic_error("result file: used after move");
  impl_->require_open();
  if (name.empty() || name == "format" || name == "format_version") {
    throw std::invalid_argument("result file: attribute name " + in_quotes(name) +
                                " is empty or reserved");
  }
  const Hdf5Scope scope;
  write_integer_attribute(impl_->file.get(), name, value, impl_->h5_path, "/");
  delete_attribute_if_present(impl_->file.get(), name + "_unit", impl_->h5_path, "/");
  impl_->flush_file();
}

void ResultFile::append_history(std::span<const double> row) {
  if (!impl_) throw std::logic_error("result file: used after move");
  Impl& m = *impl_;
  m.require_open();
  if (row.size() != m.columns.size()) {
    std::string names;
    for (const auto& column : m.columns) names += (names.empty() ? "" : ", ") + column.first;
    throw std::invalid_argument("result file '" + m.h5_path.string() + "': history row has " +
                                std::to_string(row.size()) + " values but there are " +
                                std::to_string(m.columns.size()) + " columns (" + names + ")");
  }
  if (m.columns.empty()) return;
  m.pending_history.insert(m.pending_history.end(), row.begin(), row.end());
  if (m.pending_history.size() >= k_history_flush_rows * m.columns.size()) {
    const Hdf5Scope scope;
    m.write_pending_history();
    m.flush_file();
  }
}

void ResultFile::write_snapshot(double time, std::span<const BodySnapshot> bodies) {
  if (!impl_) throw std::logic_error("result file: used after move");
  Impl& m = *impl_;
  m.require_open();
  const std::string k = std::to_string(m.snapshots.size());
  const std::string where = "result file '" + m.h5_path.string() + "': snapshot " + k + ": ";

  // Check everything before writing anything, so a bad call leaves no partial snapshot.
  if (!std::isfinite(time)) throw std::invalid_argument(where + "time is not finite");
  if (!m.snapshots.empty() && time < m.snapshots.back().time) {
    throw std::invalid_argument(where + "time " + exact_text(time) + " s is before the previous " +
                                exact_text(m.snapshots.back().time) + " s");
  }
  const std::vector<const BodySnapshot*> by_body = m.snapshots_by_body(bodies, where);
  for (std::size_t b = 0; b < m.bodies.size(); ++b) m.check_body_snapshot(b, by_body[b], where);

  const Hdf5Scope scope;
  const std::filesystem::path& file = m.h5_path;
  const std::string snapshot_path = "/snapshots/" + k;
  Handle group = create_group(m.snapshots_group.get(), k, file, snapshot_path);
  write_double_attribute(group.get(), "time", time, file, snapshot_path);
  write_text_attribute(group.get(), "time_unit", "s", file, snapshot_path);
  XdmfSnapshot record;
  record.time = time;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    record.body_fields.push_back(m.write_body_snapshot(group.get(), snapshot_path, b, *by_body[b]));
  }
  m.write_pending_history();
  m.flush_file();
  m.snapshots.push_back(std::move(record));
  m.write_xmf();
}

void ResultFile::close() {
  if (!impl_ || impl_->closed) return;
  Impl& m = *impl_;
  m.closed = true;
  const Hdf5Scope scope;
  std::exception_ptr error;
  try {
    m.write_pending_history();
  } catch (...) {
    error = std::current_exception();
  }
  m.history_datasets.clear();
  m.snapshots_group.reset();
  if (m.file.close() < 0 && !error) {
    try {
      fail(m.h5_path, "cannot close");
    } catch (...) {
      error = std::current_exception();
    }
  }
  try {
    m.write_xmf();
  } catch (...) {
    if (!error) error = std::current_exception();
  }
  if (error) std::rethrow_exception(error);
}

ResultSummary read_result_summary(const std::filesystem::path& h5_path) {
  const Hdf5Scope scope;
  Handle file = open_file_read_only(h5_path);
  ResultSummary summary;

  std::vector<std::string> names;
  check(
      H5Aiterate2(file.get(), H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_attribute_name, &names),
      h5_path, "cannot list the root attributes");
  for (const std::string& name : names) {
    const std::string what = "cannot read attribute " + in_quotes(name) + " on '/'";
    Handle attr = checked(H5Aopen(file.get(), name.c_str(), H5P_DEFAULT), H5Aclose, h5_path, what);
    Handle type = checked(H5Aget_type(attr.get()), H5Tclose, h5_path, what);
    const H5T_class_t type_class = H5Tget_class(type.get());
    if (attribute_points(attr.get(), h5_path, what) != 1) continue;  // not ours: arrays
    if (type_class == H5T_STRING) {
      summary.text_attributes[name] = read_text(attr.get(), h5_path, what);
    } else if (type_class == H5T_INTEGER || type_class == H5T_FLOAT) {
      summary.number_attributes[name] = read_number(attr.get(), h5_path, what);
    }
  }

  const htri_t has_history = H5Lexists(file.get(), "history", H5P_DEFAULT);
  if (has_history < 0) fail(h5_path, "cannot look up '/history'");
  if (has_history > 0) {
    Handle group = checked(H5Gopen2(file.get(), "history", H5P_DEFAULT), H5Gclose, h5_path,
                           "cannot open '/history'");
    summary.history_columns = link_names(group.get(), h5_path, "/history");
    // A column cut short (a run stopped while appending) limits the complete rows.
    bool first = true;
    for (const std::string& column : summary.history_columns) {
      const std::string path = "/history/" + column;
      Handle dataset = checked(H5Dopen2(group.get(), column.c_str(), H5P_DEFAULT), H5Dclose,
                               h5_path, "no dataset " + in_quotes(path));
      const std::vector<hsize_t> dims = dataset_dims(dataset.get(), h5_path, path);
      const std::size_t rows = dims.empty() ? 1 : static_cast<std::size_t>(dims[0]);
      summary.history_rows = first ? rows : std::min(summary.history_rows, rows);
      first = false;
    }
  }

  const htri_t has_snapshots = H5Lexists(file.get(), "snapshots", H5P_DEFAULT);
  if (has_snapshots < 0) fail(h5_path, "cannot look up '/snapshots'");
  if (has_snapshots > 0) {
    Handle group = checked(H5Gopen2(file.get(), "snapshots", H5P_DEFAULT), H5Gclose, h5_path,
                           "cannot open '/snapshots'");
    H5G_info_t info;
    check(H5Gget_info(group.get(), &info), h5_path, "cannot list '/snapshots'");
    summary.snapshots = static_cast<std::size_t>(info.nlinks);
  }
  return summary;
}

std::vector<double> read_history(const std::filesystem::path& h5_path, const std::string& column) {
  const Hdf5Scope scope;
  Handle file = open_file_read_only(h5_path);
  return read_dataset_values<double>(file.get(), "/history/" + column, H5T_NATIVE_DOUBLE, h5_path);
}

std::string read_unit(const std::filesystem::path& h5_path, const std::string& dataset_path) {
  const Hdf5Scope scope;
  Handle file = open_file_read_only(h5_path);
  Handle object = open_object(file.get(), dataset_path, h5_path);
  return read_text_attribute(object.get(), "unit", h5_path, dataset_path);
}

std::vector<double> read_snapshot_field(const std::filesystem::path& h5_path, std::size_t snapshot,
                                        const std::string& body, const std::string& field) {
  const Hdf5Scope scope;
  Handle file = open_file_read_only(h5_path);
  const std::string path = "/snapshots/" + std::to_string(snapshot) + "/" + body + "/" + field;
  return read_dataset_values<double>(file.get(), path, H5T_NATIVE_DOUBLE, h5_path);
}

double read_snapshot_time(const std::filesystem::path& h5_path, std::size_t snapshot) {
  const Hdf5Scope scope;
  Handle file = open_file_read_only(h5_path);
  const std::string path = "/snapshots/" + std::to_string(snapshot);
  Handle group = open_object(file.get(), path, h5_path);
  return read_number_attribute(group.get(), "time", h5_path, path);
}

std::vector<int> read_connectivity(const std::filesystem::path& h5_path, const std::string& body) {
  const Hdf5Scope scope;
  Handle file = open_file_read_only(h5_path);
  return read_dataset_values<int>(file.get(), "/bodies/" + body + "/connectivity", H5T_NATIVE_INT,
                                  h5_path);
}

std::optional<std::vector<std::size_t>> read_dataset_shape(const std::filesystem::path& h5_path,
                                                           const std::string& object_path) {
  const Hdf5Scope scope;
  Handle file = open_file_read_only(h5_path);
  if (!object_exists(file.get(), object_path, h5_path)) return std::nullopt;
  Handle object = open_object(file.get(), object_path, h5_path);
  if (H5Iget_type(object.get()) != H5I_DATASET) return std::nullopt;
  std::vector<std::size_t> shape;
  for (hsize_t d : dataset_dims(object.get(), h5_path, object_path)) {
    shape.push_back(static_cast<std::size_t>(d));
  }
  return shape;
}

}  // namespace splat
