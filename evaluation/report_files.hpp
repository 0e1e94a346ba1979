#pragma once
// The files of one report (`owsim pd`: pd.csv, pd.json, pd.svg; `owsim roc`: roc.*), replaced
// together: each is written whole under its temporary name (io/files/atomic_output_file.hpp), and
// only when every one is written, and no final name is held by something a file cannot replace (a
// directory), are they renamed — so a failure leaves every earlier report file as it was.
#include <filesystem>
#include <span>
#include <string>

namespace owsim {

// Digits after the point of every proportion (a Pd and its interval's ends) in pd.csv and roc.csv.
inline constexpr int kProportionDecimals = 12;

struct ReportFile {
  std::string name;  // in the report's folder: "pd.csv"
  std::string text;  // the whole file, rendered before anything is written
};

// Creates `directory` when missing and writes `files` into it. Throws owsim::Error naming the
// folder or the file that cannot be written; none of `files` is replaced then.
void write_report_files(const std::filesystem::path& directory, std::span<const ReportFile> files);

}  // namespace owsim
