#pragma once
// roc.svg of `owsim roc`: Pd within W (y, 0–1) against false returns per second (x, log scale;
// with --detections: the warning Pd against false warnings per flight hour; a
// value with none sits at a "0" column left of the axis), one point per value of the key with
// its Clopper–Pearson interval as a bar and the band between the bars, points joined in order of
// the value and labelled with it. A value without windows has no point.
#include <string>

#include "evaluation/roc_report.hpp"

namespace owsim {

[[nodiscard]] std::string roc_svg(const RocReport& report, const RocOptions& options);

}  // namespace owsim
