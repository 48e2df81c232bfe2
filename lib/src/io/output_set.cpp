#include "impactkit/io/output_set.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "impactkit/core/errors.hpp"

namespace impactkit {

AtomicOutputFile& OutputSet::AddFile(const std::filesystem::path& path) {
  const std::filesystem::path normal = path.lexically_normal();
  for (const auto& file : files_) {
    if (file->Path().lexically_normal() == normal) {
      throw InvalidInput(fmt::format("{} is named twice among the outputs", path.string()));
    }
  }
  files_.push_back(std::make_unique<AtomicOutputFile>(path));
  return *files_.back();
}

CsvWriter& OutputSet::AddCsv(const std::filesystem::path& path, std::string_view provenance,
                             const std::vector<std::string>& columns) {
  AtomicOutputFile& file = AddFile(path);
  try {
    tables_.push_back(std::make_unique<CsvWriter>(file, provenance, columns));
  } catch (...) {
    files_.pop_back();  // no temporary for a table that was refused
    throw;
  }
  return *tables_.back();
}

CsvWriter& OutputSet::AddCsv(AtomicOutputFile& file, std::string_view provenance,
                             const std::vector<std::string>& columns) {
  bool ours = false;
  for (const auto& owned : files_) ours = ours || owned.get() == &file;
  if (!ours) throw std::invalid_argument(file.Path().string() + " is not a file of this set");
  tables_.push_back(std::make_unique<CsvWriter>(file, provenance, columns));
  return *tables_.back();
}

void OutputSet::Commit() {
  for (const auto& table : tables_) table->Finish();
  for (const auto& file : files_) file->Close();
  for (const auto& file : files_) file->Commit();
}

}  // namespace impactkit
