#pragma once
// A time-series CSV file: one header line, a fixed number of numeric columns, every value in
// the shortest text that reads back to the same double. Each row is written and flushed at
// once, so the rows written before a crash are kept (a growing log cannot be written whole
// and renamed; the header is, though, and resume() rewrites through a temporary file).
// A table known in full is written whole instead, through a temporary file: write_csv.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/io/atomic_file.hpp"
#include "cosmpm/io/detail/number_text.hpp"

namespace cosmpm::io {

namespace detail {
inline void check_csv_columns(const std::filesystem::path& path,
                              const std::vector<std::string>& columns) {
  require(!columns.empty(), "CsvWriter: '" + path.string() + "' needs at least one column");
  for (const auto& column : columns) {
    require(!column.empty() && column.find_first_of(",\n\r\"") == std::string::npos,
            "CsvWriter: column name '" + column + "' of '" + path.string() +
                "' must be non-empty without commas, quotes or line breaks");
  }
}
}  // namespace detail

// Writes a whole table (a header and rows of the same width) through a temporary file and a
// rename: the file appears complete or not at all; errors name the file and the reason.
inline void write_csv(const std::filesystem::path& path, const std::vector<std::string>& columns,
                      const std::vector<std::vector<double>>& rows) {
  detail::check_csv_columns(path, columns);
  std::string text;
  for (std::size_t i = 0; i < columns.size(); ++i) text += (i > 0 ? "," : "") + columns[i];
  text += '\n';
  for (const auto& row : rows) {
    if (row.size() != columns.size()) {
      throw Error("write_csv: a row of '" + path.string() + "' has " + std::to_string(row.size()) +
                  " values but the file has " + std::to_string(columns.size()) + " columns");
    }
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (i > 0) text += ',';
      text += detail::format_number_exact(row[i]);
    }
    text += '\n';
  }
  if (path.has_parent_path()) create_directories(path.parent_path(), "write_csv");
  write_file_atomically(path, text);
}

class CsvWriter {
 public:
  // Creates (truncates) `path` and writes the header.
  CsvWriter(std::filesystem::path path, std::vector<std::string> columns)
      : path_(std::move(path)), columns_(std::move(columns)) {
    check_columns();
    if (path_.has_parent_path()) create_directories(path_.parent_path(), "CsvWriter");
    write_file_atomically(path_, header() + "\n");
    open_for_append();
  }

  // After a restart at `time`: keeps the header and the rows whose first column is <= time,
  // drops later rows (they will be written again) and appends from there. The file must
  // exist with the same header.
  static CsvWriter resume(std::filesystem::path path, std::vector<std::string> columns,
                          double time) {
    CsvWriter writer(std::move(path), std::move(columns), Resume{});
    std::ifstream in(writer.path_);
    if (!in) throw Error("CsvWriter::resume: cannot open '" + writer.path_.string() + "'");
    std::string line;
    std::getline(in, line);
    if (line != writer.header()) {
      throw Error("CsvWriter::resume: '" + writer.path_.string() + "' has the header '" + line +
                  "' but '" + writer.header() + "' was expected");
    }
    std::string kept = line + "\n";
    while (std::getline(in, line)) {
      if (line.empty() || line.back() == '\r') break;
      const std::size_t comma = line.find(',');
      const std::string first = line.substr(0, comma);
      char* end = nullptr;
      const double value = std::strtod(first.c_str(), &end);
      if (end == first.c_str() || !(value <= time)) break;
      kept += line + "\n";
    }
    in.close();
    write_file_atomically(writer.path_, kept);
    writer.open_for_append();
    return writer;
  }

  const std::filesystem::path& path() const { return path_; }
  const std::vector<std::string>& columns() const { return columns_; }

  void write_row(std::span<const double> values) {
    if (values.size() != columns_.size()) {
      throw Error("CsvWriter: a row of '" + path_.string() + "' has " +
                  std::to_string(values.size()) + " values but the file has " +
                  std::to_string(columns_.size()) + " columns");
    }
    std::string line;
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (i > 0) line += ',';
      line += detail::format_number_exact(values[i]);
    }
    line += '\n';
    out_.write(line.data(), static_cast<std::streamsize>(line.size()));
    out_.flush();
    if (!out_) throw Error("CsvWriter: writing a row to '" + path_.string() + "' failed");
  }
  void write_row(std::initializer_list<double> values) {
    write_row(std::span<const double>(values.begin(), values.size()));
  }

 private:
  struct Resume {};
  CsvWriter(std::filesystem::path path, std::vector<std::string> columns, Resume)
      : path_(std::move(path)), columns_(std::move(columns)) {
    check_columns();
  }

  void check_columns() const { detail::check_csv_columns(path_, columns_); }

  std::string header() const {
    std::string line;
    for (std::size_t i = 0; i < columns_.size(); ++i) line += (i > 0 ? "," : "") + columns_[i];
    return line;
  }

  void open_for_append() {
    out_.open(path_, std::ios::binary | std::ios::app);
    if (!out_) throw Error("CsvWriter: cannot open '" + path_.string() + "' for appending");
  }

  std::filesystem::path path_;
  std::vector<std::string> columns_;
  std::ofstream out_;
};

}  // namespace cosmpm::io
