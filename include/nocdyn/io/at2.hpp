// Ground-motion records in the PEER AT2 format (NGA strong-motion database):
//
//   line 1-3  free text (title, event, units: the values are in g)
//   line 4    the number of points and the time step, in one of the three forms found in the
//             database:  "NPTS=  3000, DT=   .0100 SEC",  "NPTS=   1451, dt=  .02000"  or
//             "3930 0.00500 NPTS, DT"  (keys in any case)
//   line 5-   the accelerations in g, any number of values per line separated by blanks
//
// Lines end in LF, CR LF, CR CR LF or a lone CR. Values are read as Fortran writes them: a D
// exponent (1.0D-03) is an E exponent, and values filling their fixed-width fields to the edge
// (-0.1234E-02-0.5678E-03) are split where a sign follows anything but an exponent letter.
//
// A file with fewer or more values than NPTS is refused (the header or the data is wrong, and
// neither may cut the record silently); only zeros after the NPTS-th value on its own line
// are taken as padding and ignored. Reads are bounded: at most kMaxAt2Bytes and kMaxAt2Points.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace nocdyn::io {

inline constexpr std::size_t kMaxAt2Bytes = std::size_t{64} << 20;  // 64 MiB
inline constexpr std::size_t kMaxAt2Points = 10'000'000;
/// Standard gravity [m/s^2] that converts the record's g to SI.
inline constexpr double kStandardGravity = 9.80665;

/// One component of a ground-motion record, uniformly sampled from t = 0.
struct GroundMotionRecord {
    std::string source;  ///< file it was read from
    std::string title;   ///< the first header line
    /// The second header line (event, date, station and, in NGA-West2 files, the component's
    /// orientation last: "Imperial Valley-02, 5/19/1940, El Centro Array #9, 180"), blanks folded.
    std::string event;
    double dt = 0.0;                   ///< time step [s]
    std::vector<double> acceleration;  ///< [m/s^2] (the file's g times kStandardGravity)

    /// Duration (n - 1) dt [s].
    [[nodiscard]] double duration() const;
};

/// Parses AT2 text; `source` names it in errors. Throws nocdyn::Error "SOURCE:LINE: reason"
/// for a short or malformed header, a bad NPTS or DT, a value that is not a finite decimal
/// number, or fewer values than NPTS (naming the last line read).
[[nodiscard]] GroundMotionRecord parseAt2(const std::string& text, const std::string& source);

/// Reads an AT2 file (a regular file of at most kMaxAt2Bytes). Throws nocdyn::Error.
[[nodiscard]] GroundMotionRecord readAt2File(const std::string& path);

}  // namespace nocdyn::io
