// Choropleth classification: class breaks for numeric values (quantile, equal interval, Jenks
// natural breaks, R's pretty) following R's classInt::classIntervals, and the ColorBrewer 2.0
// sequential and diverging colour ramps. Pure computation: no GDAL, no I/O.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace globe {

enum class ClassMethod { kQuantile, kEqual, kJenks, kPretty };

// "quantile", "equal", "jenks", "pretty" (exactly these spellings); nullopt otherwise.
std::optional<ClassMethod> parse_class_method(std::string_view name);
const char* class_method_name(ClassMethod m);

// Breaks b0 < b1 < ... < bk of the finite values (NaN and infinities are skipped) into k classes.
// Class i holds [b_i, b_{i+1}); the last class is closed on both sides, [b_{k-1}, b_k]. k is
// `classes` unless breaks repeat (repeated values: duplicate breaks are removed, so k is fewer)
// or the method is pretty (whose k is its own). A single distinct value v gives one class:
// the breaks {v, v}, the one case where two breaks are equal.
//  - quantile: R's quantile(type = 7) at probs seq(0, 1, 1/classes), as classInt "quantile".
//  - equal:    min + i * (max - min) / classes, the last break exactly max (classInt "equal").
//  - jenks:    Jenks natural breaks: the exact optimal partition of the sorted values into
//              contiguous classes minimising the within-class sum of squared deviations
//              (Fisher's algorithm, a dynamic programme). The breaks are min, then the smallest
//              value of each class but the first, then max: the partition classInt's "jenks"
//              style gives, whose breaks are each class's largest value read with intervals
//              closed on the right; here, as for every method, intervals are closed on the left,
//              so each class's lowest value is its break and every value keeps its optimal
//              class; when the top class is the maximum alone, the last two breaks are both the
//              maximum (that class is [max, max]). The programme runs on the sorted distinct values
//              weighted by their counts, which is exact, in O(d log d * classes) for d distinct
//              values (the best class starts are monotone, so divide and conquer finds them). With
//              more than 5,000 distinct values it runs instead on 5,000 order statistics at evenly
//              spaced ranks (the minimum and maximum among them), each of weight one: exact Jenks
//              on that sample, an approximation for the whole; its breaks are still values of the
//              data.
//  - pretty:   R's pretty(range(values), n = classes) (R_pretty with its defaults: min.n =
//              classes %/% 3, shrink.sml = 0.75, high.u.bias = 1.5, u5.bias = 2.75,
//              eps.correct = 0, bounds = TRUE): equally spaced round breaks covering the range.
// Throws std::invalid_argument for classes < 2 or > 12, or no finite value.
std::vector<double> class_breaks(std::span<const double> values, int classes, ClassMethod method);

// Index of the class holding v under the semantics above (0..k-1, k = breaks.size() - 1); -1 for
// NaN or infinite v, v outside [b0, bk], or fewer than two breaks.
int class_of(double v, std::span<const double> breaks);

enum class RampType { kSequential, kDiverging };
struct ColorRamp {
  const char* name;
  RampType type;
  int min_classes, max_classes;
};

// Every ramp known: the ColorBrewer 2.0 sequential schemes (3 to 9 classes) YlOrRd YlOrBr YlGnBu
// YlGn Reds RdPu Purples PuRd PuBuGn PuBu OrRd Oranges Greys Greens GnBu BuPu BuGn Blues, and the
// diverging ones (3 to 11 classes) Spectral RdYlGn RdYlBu RdGy RdBu PuOr PRGn PiYG BrBG.
std::span<const ColorRamp> color_ramps();

// The ramp's colours for `classes` classes as "#rrggbb" (lowercase hex), ColorBrewer's exact
// values for that class count, in ColorBrewer's order; the name is matched case-insensitively.
// nullopt for an unknown name or a class count the ramp lacks.
std::optional<std::vector<std::string>> ramp_colors(std::string_view name, int classes);

}  // namespace globe
