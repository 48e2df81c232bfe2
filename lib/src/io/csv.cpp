#include "impactkit/io/csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>

namespace impactkit {
namespace {

constexpr std::size_t kFlushBytes = 1 << 16;

}  // namespace

std::string CsvField(double value) { return std::isnan(value) ? "" : fmt::format("{}", value); }

std::string CsvHead(const std::vector<std::string>& columns, std::string_view provenance) {
  if (columns.empty()) throw std::invalid_argument("a CSV table needs at least one column");
  if (provenance.find('\r') != std::string_view::npos) {
    throw std::invalid_argument("a CSV comment must not contain a carriage return");
  }
  std::string head = fmt::format("{}\n", fmt::join(columns, ","));
  for (std::size_t begin = 0; begin < provenance.size();) {
    const std::size_t end = std::min(provenance.find('\n', begin), provenance.size());
    fmt::format_to(std::back_inserter(head), "# {}\n", provenance.substr(begin, end - begin));
    begin = end + 1;
  }
  return head;
}

CsvWriter::CsvWriter(const std::filesystem::path& path, std::string_view provenance,
                     const std::vector<std::string>& columns)
    : owned_(std::in_place, path),
      file_(&*owned_),
      columns_(columns.size()),
      buffer_(CsvHead(columns, provenance)) {}

CsvWriter::CsvWriter(AtomicOutputFile& file, std::string_view provenance,
                     const std::vector<std::string>& columns)
    : file_(&file), columns_(columns.size()), buffer_(CsvHead(columns, provenance)) {}

void CsvWriter::WriteRow(std::span<const double> values) {
  if (values.size() != columns_) {
    throw std::invalid_argument(fmt::format("a row of {} needs {} values, got {}", Path().string(),
                                            columns_, values.size()));
  }
  // "{}" is the shortest representation that round-trips (fmt's default).
  fmt::format_to(std::back_inserter(buffer_), "{}\n", fmt::join(values, ","));
  if (buffer_.size() >= kFlushBytes) Finish();
}

void CsvWriter::WriteRow(std::span<const double> values, std::span<const std::string> labels) {
  if (values.size() + labels.size() != columns_) {
    throw std::invalid_argument(fmt::format("a row of {} needs {} values, got {}", Path().string(),
                                            columns_, values.size() + labels.size()));
  }
  for (const std::string& label : labels) {
    if (label.find_first_of(",\r\n\"") != std::string::npos) {
      throw std::invalid_argument(
          fmt::format("a CSV label must have no comma, quote or line "
                      "break, got '{}'",
                      label));
    }
  }
  fmt::format_to(std::back_inserter(buffer_), "{}{}{}\n", fmt::join(values, ","),
                 values.empty() || labels.empty() ? "" : ",", fmt::join(labels, ","));
  if (buffer_.size() >= kFlushBytes) Finish();
}

void CsvWriter::Commit() {
  Finish();
  file_->Commit();
}

void CsvWriter::Finish() {
  file_->Write(buffer_);
  buffer_.clear();
}

}  // namespace impactkit
