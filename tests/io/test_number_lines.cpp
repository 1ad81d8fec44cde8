#include <doctest/doctest.h>

#include <omp.h>

#include <algorithm>
#include <string>
#include <vector>

#include "core/base/errors.h"
#include "io/number_lines.h"

using hermite::InputError;
using hermite::NumberLines;

namespace {

// The serial loop parseNumberLines stands for: its lines, or the message of its first bad line.
NumberLines serialLines(std::string_view text, int capacity, const std::string& path, std::string& error) {
  NumberLines out;
  hermite::LineReader lines(text);
  std::string_view line;
  long number = 0;
  std::vector<double> values(static_cast<std::size_t>(capacity));
  try {
    while (lines.next(line, number)) {
      std::fill(values.begin(), values.end(), 0.0);
      out.counts.push_back(hermite::parseNumbers(line, values.data(), capacity, path, number));
      out.values.insert(out.values.end(), values.begin(), values.end());
      out.numbers.push_back(number);
    }
  } catch (const InputError& e) {
    error = e.what();
  }
  return out;
}

std::string messageOf(const std::exception_ptr& e) {
  if (!e) return "";
  try {
    std::rethrow_exception(e);
  } catch (const InputError& x) {
    return x.what();
  }
}

// About 1.2 MB of "x y z nx ny nz" lines (several chunks), with blank, comment and CRLF lines.
std::string bigText() {
  std::string text = "\xEF\xBB\xBF# header\n";
  for (int i = 0; i < 30000; ++i) {
    text += std::to_string(i) + " " + std::to_string(0.5 * i) + " -1e-3 0 0 1" + (i % 7 == 0 ? "\r\n" : "\n");
    if (i % 1000 == 0) text += "\n   # comment\n";
  }
  return text;
}

}  // namespace

TEST_CASE("io_number_lines: parallel chunks read the lines, numbers and first error of the serial loop") {
  const int saved = omp_get_max_threads();
  const std::string good = bigText();
  for (int threads : {1, 2, 4}) {
    omp_set_num_threads(threads);
    CAPTURE(threads);
    // Whole file; a bad token late in the file; a bad line at a chunk's very start; a short line
    // (a count the caller rejects) before a bad token.
    std::string late = good, start = good, counts = good;
    late.replace(late.size() - 40, 1, "x");
    const std::size_t cut = good.find('\n', good.size() / 2) + 1;
    start.insert(cut, "1 2 zz\n");
    counts.insert(cut, "1 2 3\n");
    counts.replace(counts.size() - 40, 1, "nan ");
    for (const std::string* text : std::vector<const std::string*>{&good, &late, &start, &counts}) {
      std::string want;
      const NumberLines serial = serialLines(*text, 6, "f.xyz", want);
      const NumberLines parallel = hermite::parseNumberLines(*text, 6, "f.xyz");
      CHECK(parallel.counts == serial.counts);
      CHECK(parallel.numbers == serial.numbers);
      CHECK(parallel.values == serial.values);
      CHECK(messageOf(parallel.error) == want);
    }
  }
  omp_set_num_threads(saved);
  const NumberLines small = hermite::parseNumberLines("1 2\n\n# c\n3 4 5\nq\n6\n", 2, "s.txt");
  CHECK(small.counts == std::vector<int>{2, 3});
  CHECK(small.numbers == std::vector<long>{1, 4});
  CHECK(small.values == std::vector<double>{1, 2, 3, 4});
  CHECK(messageOf(small.error) == "s.txt:5: 'q' is not a number");
}
