#include "store/study_store.hpp"

#include "io/files.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace nsb::store {

namespace fs = std::filesystem;

// A CSV file as nsbridge writes it (io/csv.hpp, RFC 4180): the header, then the rows, a quoted
// field possibly holding commas, doubled quotes and line breaks.
struct CsvText {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

namespace {

// An HDF5 identifier closed by its own function when it goes out of scope.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, -1)), close_(other.close_) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle& operator=(Handle&&) = delete;
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

// HDF5's own calls report through its error stack; the store reports through exceptions that
// name the file, so the stack's printing is switched off.
void quiet_hdf5() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

[[noreturn]] void write_failed(const fs::path& file, const std::string& what) {
  throw io::WriteError("cannot write '" + file.string() + "': HDF5 could not " + what +
                       " (a full disk, or a damaged file: remove it and rerun to make it again "
                       "from the run folders)");
}

// A UTF-8 string type of variable length, as h5py reads into str.
Handle string_type() {
  Handle t(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(t.get(), H5T_VARIABLE);
  H5Tset_cset(t.get(), H5T_CSET_UTF8);
  return t;
}

bool write_string_attribute(hid_t object, const char* name, const std::string& value) {
  const Handle type = string_type();
  const Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  const Handle a(H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                 H5Aclose);
  const char* text = value.c_str();
  return a.ok() && H5Awrite(a.get(), type.get(), &text) >= 0;
}

bool write_strings_attribute(hid_t object, const char* name,
                             const std::vector<std::string>& values) {
  const Handle type = string_type();
  const hsize_t n = values.size();
  const Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  const Handle a(H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                 H5Aclose);
  std::vector<const char*> texts;
  for (const auto& v : values) texts.push_back(v.c_str());
  return a.ok() && H5Awrite(a.get(), type.get(), texts.data()) >= 0;
}

bool write_int_attribute(hid_t object, const char* name, std::int64_t value) {
  const Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  const Handle a(H5Acreate2(object, name, H5T_STD_I64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                 H5Aclose);
  return a.ok() && H5Awrite(a.get(), H5T_NATIVE_INT64, &value) >= 0;
}

// A string attribute the store wrote; "" when it is absent or of another type.
std::string read_string_attribute(hid_t object, const char* name) {
  if (H5Aexists(object, name) <= 0) return "";
  const Handle a(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
  const Handle stored(H5Aget_type(a.get()), H5Tclose);
  if (H5Tget_class(stored.get()) != H5T_STRING || H5Tis_variable_str(stored.get()) <= 0) return "";
  const Handle type = string_type();
  char* text = nullptr;
  if (H5Aread(a.get(), type.get(), &text) < 0 || text == nullptr) return "";
  std::string value(text);
  H5free_memory(text);
  return value;
}

bool write_strings(hid_t group, const std::string& name, const std::vector<std::string>& values) {
  const Handle type = string_type();
  const hsize_t n = values.size();
  const Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  const Handle d(H5Dcreate2(group, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT,
                            H5P_DEFAULT),
                 H5Dclose);
  std::vector<const char*> texts;
  for (const auto& v : values) texts.push_back(v.c_str());
  return d.ok() && (values.empty() || H5Dwrite(d.get(), type.get(), H5S_ALL, H5S_ALL,
                                               H5P_DEFAULT, texts.data()) >= 0);
}

bool write_string(hid_t group, const char* name, const std::string& value) {
  const Handle type = string_type();
  const Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  const Handle d(
      H5Dcreate2(group, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
      H5Dclose);
  const char* text = value.c_str();
  return d.ok() && H5Dwrite(d.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &text) >= 0;
}

// A history is chunked column by column, 16384 samples (128 kB) a chunk: shuffle and deflate
// then see one smooth series at a time (a quarter smaller than chunks of whole rows on the
// benchmark bridge's histories, docs/outputs.md), and reading one column decompresses only
// that column.
constexpr hsize_t kChunkSamples = 16384;
// zlib's level 4: within 1 % of level 9's size on histories, several times faster.
constexpr unsigned kDeflateLevel = 4;

// A samples x columns table of doubles (row-major in memory), chunked by column, shuffled and
// deflated.
bool write_matrix(hid_t group, const char* name, const std::vector<double>& values, hsize_t rows,
                  hsize_t columns) {
  const hsize_t dims[2] = {rows, columns};
  const Handle space(H5Screate_simple(2, dims, nullptr), H5Sclose);
  const Handle create(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (rows > 0 && columns > 0) {
    const hsize_t chunk[2] = {std::min(kChunkSamples, rows), 1};
    H5Pset_chunk(create.get(), 2, chunk);
    H5Pset_shuffle(create.get());
    H5Pset_deflate(create.get(), kDeflateLevel);
  }
  const Handle d(H5Dcreate2(group, name, H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, create.get(),
                            H5P_DEFAULT),
                 H5Dclose);
  return d.ok() && (values.empty() || H5Dwrite(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL,
                                               H5P_DEFAULT, values.data()) >= 0);
}

bool write_doubles(hid_t group, const std::string& name, const std::vector<double>& values) {
  const hsize_t n = values.size();
  const Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  const Handle d(H5Dcreate2(group, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT,
                            H5P_DEFAULT, H5P_DEFAULT),
                 H5Dclose);
  return d.ok() && (values.empty() || H5Dwrite(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL,
                                               H5P_DEFAULT, values.data()) >= 0);
}

bool write_integers(hid_t group, const std::string& name, const std::vector<std::int64_t>& values) {
  const hsize_t n = values.size();
  const Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  const Handle d(H5Dcreate2(group, name.c_str(), H5T_STD_I64LE, space.get(), H5P_DEFAULT,
                            H5P_DEFAULT, H5P_DEFAULT),
                 H5Dclose);
  return d.ok() && (values.empty() || H5Dwrite(d.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL,
                                               H5P_DEFAULT, values.data()) >= 0);
}

CsvText parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> lines;
  std::vector<std::string> fields;
  std::string field;
  bool quoted = false, any = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (quoted) {
      if (ch == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (ch == '"') {
        quoted = false;
      } else {
        field += ch;
      }
    } else if (ch == '"') {
      quoted = true;
      any = true;
    } else if (ch == ',') {
      fields.push_back(std::move(field));
      field.clear();
      any = true;
    } else if (ch == '\n') {
      fields.push_back(std::move(field));
      field.clear();
      lines.push_back(std::move(fields));
      fields.clear();
      any = false;
    } else if (ch != '\r') {
      field += ch;
      any = true;
    }
  }
  if (any) {
    fields.push_back(std::move(field));
    lines.push_back(std::move(fields));
  }
  CsvText csv;
  if (lines.empty()) return csv;
  csv.header = std::move(lines.front());
  csv.rows.assign(std::make_move_iterator(lines.begin() + 1), std::make_move_iterator(lines.end()));
  return csv;
}

// A field as a double: the shortest round-trip text io::csv_number writes reads back exactly
// (std::from_chars rounds correctly); an empty field is a non-finite value, NaN here.
bool parse_double(const std::string& s, double& v) {
  if (s.empty()) {
    v = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  return ec == std::errc() && end == s.data() + s.size();
}

bool parse_integer(const std::string& s, std::int64_t& v) {
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  return !s.empty() && ec == std::errc() && end == s.data() + s.size();
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// events.csv as one dataset per column (attribute `columns`: their order): int64 when every
// field is an integer, float64 when every field is a number (an empty one NaN), else strings.
bool write_columns(hid_t group, const CsvText& csv) {
  if (!write_strings_attribute(group, "columns", csv.header)) return false;
  for (std::size_t c = 0; c < csv.header.size(); ++c) {
    std::vector<std::string> texts;
    for (const auto& row : csv.rows) texts.push_back(c < row.size() ? row[c] : std::string());
    std::vector<std::int64_t> integers(texts.size());
    std::vector<double> reals(texts.size());
    bool all_integers = true, all_reals = true;
    for (std::size_t i = 0; i < texts.size(); ++i) {
      all_integers = all_integers && parse_integer(texts[i], integers[i]);
      all_reals = all_reals && parse_double(texts[i], reals[i]);
    }
    const bool ok = all_integers ? write_integers(group, csv.header[c], integers)
                    : all_reals  ? write_doubles(group, csv.header[c], reals)
                                 : write_strings(group, csv.header[c], texts);
    if (!ok) return false;
  }
  return true;
}

}  // namespace

// A run's files as its group holds them (history.csv's kept columns, events.csv,
// summary.json), read before the group is written.
struct RunFiles {
  bool keep_history = false;
  std::vector<std::string> names;  // the kept history columns
  std::vector<double> values;      // samples x names, row-major
  hsize_t samples = 0;
  std::optional<CsvText> events;       // events.csv; none for a rejected run
  std::optional<std::string> summary;  // summary.json's text; none for a rejected run
};

namespace {

// What a run's folder holds for its group, read and parsed without HDF5, so that workers read
// their runs' files at the same time and take turns only to write. Throws
// std::invalid_argument for a column of output.hdf5_history the history lacks.
RunFiles read_run_files(const sweep::Design& d, const fs::path& dir, std::size_t index,
                        const sweep::Row& row) {
  const std::string& id = d.runs.at(index).id;
  const fs::path folder = dir / "runs" / id;
  // Every run but a rejected one has its outputs beside its row; without them (an MPI rank's
  // folder on a disk rank 0 does not see) the group would silently lack them.
  if (row.status != "rejected" && !fs::exists(folder / "summary.json")) {
    throw io::WriteError("cannot read '" + (folder / "summary.json").string() +
                         "': not found (under MPI, DIR must be on a file system every rank "
                         "shares, docs/sweep.md)");
  }
  // The kept columns of history.csv, read before the group is made, so that a column the
  // design names and the run lacks leaves no group behind.
  RunFiles files;
  const fs::path history = folder / "history.csv";
  files.keep_history =
      d.output.history != sweep::OutputSpec::History::kNone && fs::exists(history);
  if (files.keep_history) {
    const CsvText csv = parse_csv(read_text(history));
    std::vector<std::size_t> keep;
    if (d.output.history == sweep::OutputSpec::History::kAll) {
      for (std::size_t c = 0; c < csv.header.size(); ++c) keep.push_back(c);
    } else {
      std::vector<std::string> wanted = {"t"};
      for (const auto& c : d.output.columns)
        if (c != "t") wanted.push_back(c);
      for (const auto& name : wanted) {
        const auto at = std::find(csv.header.begin(), csv.header.end(), name);
        if (at == csv.header.end()) {
          std::string all;
          for (const auto& h : csv.header) all += (all.empty() ? "" : ", ") + h;
          throw std::invalid_argument(d.file.string() + ":" + std::to_string(d.output.line) +
                                      ": output.hdf5_history: run " + id + "'s history.csv has no "
                                      "column \"" + name + "\" (it has " + all + ")");
        }
        keep.push_back(static_cast<std::size_t>(at - csv.header.begin()));
      }
    }
    files.values.reserve(csv.rows.size() * keep.size());
    for (std::size_t r = 0; r < csv.rows.size(); ++r) {
      for (const std::size_t c : keep) {
        double v = 0.0;
        if (c >= csv.rows[r].size() || !parse_double(csv.rows[r][c], v)) {
          throw io::WriteError("cannot read '" + history.string() + "': line " +
                               std::to_string(r + 2) + ", column " + csv.header[c] +
                               " is not a number");
        }
        files.values.push_back(v);
      }
    }
    for (const std::size_t c : keep) files.names.push_back(csv.header[c]);
    files.samples = csv.rows.size();
  }
  if (const fs::path events = folder / "events.csv"; fs::exists(events))
    files.events = parse_csv(read_text(events));
  if (const fs::path summary = folder / "summary.json"; fs::exists(summary))
    files.summary = read_text(summary);
  return files;
}

}  // namespace

std::string history_selection(const sweep::OutputSpec& output) {
  switch (output.history) {
    case sweep::OutputSpec::History::kAll:
      return "all";
    case sweep::OutputSpec::History::kNone:
      return "none";
    case sweep::OutputSpec::History::kColumns:
      break;
  }
  std::string joined = "t";
  for (const auto& c : output.columns)
    if (c != "t") joined += "," + c;
  return joined;
}

StudyStore::StudyStore(fs::path dir, bool restart) : dir_(std::move(dir)), restart_(restart) {}

StudyStore::~StudyStore() {
  if (file_ >= 0) H5Fclose(file_);
}

void StudyStore::prepared(const sweep::Design& design,
                          const std::vector<std::optional<sweep::Row>>& rows) {
  const std::lock_guard<std::mutex> lock(mutex_);
  quiet_hdf5();
  design_ = &design;
  const fs::path f = file();
  const std::string selection = history_selection(design.output);
  std::error_code ec;
  if (restart_ && fs::is_regular_file(f)) fs::remove(f, ec);
  if (fs::is_regular_file(f)) {
    file_ = H5Fopen(f.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    if (file_ < 0) {
      notes_.push_back(f.string() + " could not be opened (a process stopped while writing it): "
                       "made again from the run folders");
      fs::remove(f, ec);
    } else {
      std::string hash = read_string_attribute(file_, "design_hash");
      if (hash != design.hash) {
        H5Fclose(file_);
        file_ = -1;
        throw std::invalid_argument(
            f.string() + ": holds the runs of a different design (design hash " +
            (hash.empty() ? std::string("unknown") : hash) + ", this design " + design.hash +
            "); use --restart to discard them, or another --out");
      }
      if (read_string_attribute(file_, "hdf5_history") != selection) {
        H5Fclose(file_);
        file_ = -1;
        notes_.push_back(f.string() + " kept other history columns (output.hdf5_history): made "
                         "again from the run folders");
        fs::remove(f, ec);
      }
    }
  }
  // An existing file keeps the groups of the runs it finished (the "done" flag is written
  // last); the table of a finished sweep and every unfinished group are deleted, to be written
  // again. A process killed while writing can leave a group HDF5 cannot delete: such a file
  // is made again from the run folders, as one that does not open.
  std::vector<bool> kept(rows.size(), false);
  if (file_ >= 0 && !keep_finished_groups(design, rows, kept)) {
    H5Fclose(file_);
    file_ = -1;
    kept.assign(rows.size(), false);
    notes_.push_back(f.string() + " holds a group that cannot be deleted (a process stopped "
                     "while writing it): made again from the run folders");
    fs::remove(f, ec);
  }
  if (file_ < 0) {
    errno = 0;
    file_ = H5Fcreate(f.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (file_ < 0) {
      throw std::invalid_argument(f.string() + ": cannot create the HDF5 file" +
                                  (errno != 0 ? std::string(": ") + std::strerror(errno) : ""));
    }
    const Handle group(H5Gcreate2(file_, "runs", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                       H5Gclose);
    if (!group.ok() || !write_string_attribute(file_, "format", "nsbridge sweep.h5") ||
        !write_int_attribute(file_, "format_version", kFormatVersion) ||
        !write_string_attribute(file_, "design", design.file.string()) ||
        !write_string_attribute(file_, "design_hash", design.hash) ||
        !write_string_attribute(file_, "revision", sweep::code_revision()) ||
        !write_string_attribute(file_, "hdf5_history", selection) ||
        !write_int_attribute(file_, "runs", static_cast<std::int64_t>(design.runs.size()))) {
      write_failed(f, "write the file's attributes");
    }
  }
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i] && !kept[i]) write_run(i, *rows[i], read_run_files(design, dir_, i, *rows[i]));
  }
  if (H5Fflush(file_, H5F_SCOPE_GLOBAL) < 0) write_failed(f, "flush the file");
}

bool StudyStore::keep_finished_groups(const sweep::Design& design,
                                      const std::vector<std::optional<sweep::Row>>& rows,
                                      std::vector<bool>& kept) {
  if (H5Lexists(file_, "results", H5P_DEFAULT) > 0 && H5Ldelete(file_, "results", H5P_DEFAULT) < 0)
    return false;
  const Handle runs(H5Gopen2(file_, "runs", H5P_DEFAULT), H5Gclose);
  if (!runs.ok()) return false;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const char* id = design.runs[i].id.c_str();
    if (H5Lexists(runs.get(), id, H5P_DEFAULT) <= 0) continue;
    bool done = false;
    {
      const Handle g(H5Gopen2(runs.get(), id, H5P_DEFAULT), H5Gclose);
      done = g.ok() && H5Aexists(g.get(), "done") > 0;
    }
    kept[i] = done && rows[i].has_value();
    if (!kept[i] && H5Ldelete(runs.get(), id, H5P_DEFAULT) < 0) return false;
  }
  return true;
}

void StudyStore::finished(std::size_t index, const sweep::Row& row) {
  const RunFiles files = read_run_files(*design_, dir_, index, row);
  const std::lock_guard<std::mutex> lock(mutex_);
  write_run(index, row, files);
}

void StudyStore::write_run(std::size_t index, const sweep::Row& row, const RunFiles& files) {
  const fs::path f = file();
  const sweep::Design& d = *design_;
  const std::string& id = d.runs.at(index).id;
  const std::string where = "/runs/" + id;
  const Handle runs(H5Gopen2(file_, "runs", H5P_DEFAULT), H5Gclose);
  const Handle g(H5Gcreate2(runs.get(), id.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                 H5Gclose);
  if (!g.ok()) write_failed(f, "create " + where);
  // The run's line of results.csv, with its header: the same text, so the same numbers.
  if (!write_int_attribute(g.get(), "index", static_cast<std::int64_t>(index)) ||
      !write_string_attribute(g.get(), "row", sweep::results_of(d, {row}).csv()))
    write_failed(f, "write the row of " + where);

  if (files.keep_history) {
    if (!write_matrix(g.get(), "history", files.values, files.samples, files.names.size()))
      write_failed(f, "write " + where + "/history");
    const Handle h(H5Dopen2(g.get(), "history", H5P_DEFAULT), H5Dclose);
    if (!write_strings_attribute(h.get(), "columns", files.names))
      write_failed(f, "write " + where + "/history's columns");
  }
  if (files.events) {
    const Handle e(H5Gcreate2(g.get(), "events", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
    if (!e.ok() || !write_columns(e.get(), *files.events))
      write_failed(f, "write " + where + "/events");
  }
  if (files.summary && !write_string(g.get(), "summary", *files.summary))
    write_failed(f, "write " + where + "/summary");
  // Written last: a group without it is one a stopped process left unfinished.
  if (!write_int_attribute(g.get(), "done", 1)) write_failed(f, "mark " + where + " done");
  if (H5Fflush(file_, H5F_SCOPE_GLOBAL) < 0) write_failed(f, "flush the file");
}

void StudyStore::completed(const sweep::Results& table) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const fs::path f = file();
  const Handle g(H5Gcreate2(file_, "results", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose);
  std::vector<std::string> names, kinds;
  for (const auto& c : table.columns) {
    names.push_back(c.name);
    kinds.push_back(std::string(sweep::to_string(c.kind)));
  }
  if (!g.ok() || !write_strings_attribute(g.get(), "columns", names) ||
      !write_strings_attribute(g.get(), "kinds", kinds))
    write_failed(f, "create /results");
  for (std::size_t c = 0; c < table.columns.size(); ++c) {
    const auto kind = table.columns[c].kind;
    bool ok = false;
    if (kind == sweep::ValueKind::kReal || kind == sweep::ValueKind::kInteger) {
      // Counts too: a rejected run has none (NaN), and every count is below 2^53.
      std::vector<double> values;
      for (const auto& row : table.rows)
        values.push_back(table.number(row, c).value_or(std::numeric_limits<double>::quiet_NaN()));
      ok = write_doubles(g.get(), table.columns[c].name, values);
    } else {
      std::vector<std::string> values;
      for (const auto& row : table.rows) values.push_back(table.cell(row, c));
      ok = write_strings(g.get(), table.columns[c].name, values);
    }
    if (!ok) write_failed(f, "write /results/" + table.columns[c].name);
  }
  if (!write_int_attribute(g.get(), "done", 1)) write_failed(f, "mark /results done");
  if (H5Fflush(file_, H5F_SCOPE_GLOBAL) < 0) write_failed(f, "flush the file");
}

}  // namespace nsb::store
