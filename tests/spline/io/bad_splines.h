#pragma once
// The bad spline files of the corpus (tests/data/bad/*.msp): each one's problem and a keyword of
// the one-line error it must give. SplineFileCorpus.DISABLED_WriteBadSplines (spline_file_test)
// writes them from a small torus; the spline-file and `msp edit` tests read them.
namespace spline::testing {

struct BadSpline {
  const char* name;
  const char* keyword;
};

inline constexpr BadSpline kBadSplines[] = {
    {"truncated.msp", "file ends inside section ATLS"},
    {"wrong_magic.msp", "not an msp spline file (bad magic bytes)"},
    {"wrong_version.msp", "format version 99 is not supported"},
    {"inconsistent_counts.msp", "inconsistent counts: the header says faces 101"},
    {"index_out_of_range.msp", "face 2 has vertex index 4096 outside"},
    {"nan_control_point.msp", "control point 5 is not finite"},
};

}  // namespace spline::testing
