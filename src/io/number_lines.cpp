#include "io/number_lines.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include <omp.h>

#include "core/base/errors.h"
#include "io/quoted_token.h"

namespace hermite {

namespace {

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Chunks of at least this many bytes (smaller files parse on the calling thread).
constexpr std::size_t kChunkBytes = std::size_t(1) << 18;

// The chunks' first bytes: `text` cut into about `want` pieces just after a line end, plus its end.
std::vector<std::size_t> chunkStarts(std::string_view text, int want) {
  std::vector<std::size_t> starts{0};
  for (int c = 1; c < want; ++c) {
    const std::size_t guess = std::max(starts.back(), text.size() * static_cast<std::size_t>(c) / want);
    const std::size_t eol = text.find('\n', guess);
    if (eol == std::string_view::npos) break;
    if (eol + 1 > starts.back()) starts.push_back(eol + 1);
  }
  starts.push_back(text.size());
  return starts;
}

// One chunk's lines (linesBefore line ends precede it), up to its first line that does not parse.
void parseChunk(std::string_view chunk, long linesBefore, int capacity, const std::string& path, NumberLines& out) {
  LineReader lines(chunk, linesBefore);
  std::string_view line;
  long number = 0;
  std::vector<double> values(static_cast<std::size_t>(capacity));
  try {
    while (lines.next(line, number)) {
      std::fill(values.begin(), values.end(), 0.0);
      const int count = parseNumbers(line, values.data(), capacity, path, number);
      out.values.insert(out.values.end(), values.begin(), values.end());
      out.counts.push_back(count);
      out.numbers.push_back(number);
    }
  } catch (const InputError&) {
    out.error = std::current_exception();
  }
}

}  // namespace

LineReader::LineReader(std::string_view text, long linesBefore)
    : p_(text.data()), end_(text.data() + text.size()), lineNumber_(linesBefore) {
  if (linesBefore == 0 && end_ - p_ >= 3 && std::memcmp(p_, "\xEF\xBB\xBF", 3) == 0) p_ += 3;
}

bool LineReader::next(std::string_view& line, long& number) {
  while (p_ < end_) {
    const char* eol = static_cast<const char*>(std::memchr(p_, '\n', static_cast<std::size_t>(end_ - p_)));
    if (!eol) eol = end_;
    const char* b = p_;
    const char* e = eol;
    p_ = eol < end_ ? eol + 1 : end_;
    ++lineNumber_;
    while (b < e && (*b == ' ' || *b == '\t')) ++b;
    while (e > b && (e[-1] == '\r' || e[-1] == ' ' || e[-1] == '\t')) --e;
    if (b == e || *b == '#') continue;
    line = std::string_view(b, static_cast<std::size_t>(e - b));
    number = lineNumber_;
    return true;
  }
  return false;
}

int parseNumbers(std::string_view line, double* values, int capacity, const std::string& path, long lineNumber) {
  int count = 0;
  const char* p = line.data();
  const char* end = p + line.size();
  while (true) {
    while (p < end && isBlank(*p)) ++p;
    if (p == end) break;
    const char* tokenBegin = p;
    while (p < end && !isBlank(*p)) ++p;
    const std::string_view token(tokenBegin, static_cast<std::size_t>(p - tokenBegin));
    auto where = [&] { return path + ":" + std::to_string(lineNumber) + ": "; };

    const char* b = token.data();
    const char* e = b + token.size();
    if (*b == '+' && e - b > 1 && (std::isdigit(static_cast<unsigned char>(b[1])) || b[1] == '.')) ++b;
    double v = 0;
    const auto r = std::from_chars(b, e, v);
    if (r.ec == std::errc::invalid_argument || r.ptr != e)
      throw InputError(where() + quotedToken(token) + " is not a number");
    if (r.ec == std::errc::result_out_of_range) {
      // from_chars reports both overflow and underflow; strtod tells them apart (underflow → 0).
      const std::string copy(b, e);
      v = std::strtod(copy.c_str(), nullptr);
    }
    if (!std::isfinite(v))
      throw InputError(where() + quotedToken(token) + " is not a finite number");
    if (count < capacity) values[count] = v;
    ++count;
  }
  return count;
}

NumberLines parseNumberLines(std::string_view text, int capacity, const std::string& path) {
  const int threads = omp_get_max_threads();
  const int want = std::clamp(static_cast<int>(text.size() / kChunkBytes), 1, 4 * threads);
  const std::vector<std::size_t> starts = chunkStarts(text, want);
  const int chunks = static_cast<int>(starts.size()) - 1;
  std::vector<long> linesBefore(static_cast<std::size_t>(chunks) + 1, 0);
#pragma omp parallel for schedule(static)
  for (int c = 0; c < chunks; ++c)
    linesBefore[static_cast<std::size_t>(c) + 1] =
        static_cast<long>(std::count(text.begin() + starts[c], text.begin() + starts[c + 1], '\n'));
  for (int c = 0; c < chunks; ++c) linesBefore[static_cast<std::size_t>(c) + 1] += linesBefore[static_cast<std::size_t>(c)];
  std::vector<NumberLines> parts(static_cast<std::size_t>(chunks));
#pragma omp parallel for schedule(dynamic, 1)
  for (int c = 0; c < chunks; ++c)
    parseChunk(text.substr(starts[c], starts[c + 1] - starts[c]), linesBefore[static_cast<std::size_t>(c)], capacity,
               path, parts[static_cast<std::size_t>(c)]);
  // In file order up to the first chunk that stopped at a bad line: the lines after it are not read.
  NumberLines out = std::move(parts[0]);
  for (int c = 1; c < chunks && !out.error; ++c) {
    NumberLines& p = parts[static_cast<std::size_t>(c)];
    out.values.insert(out.values.end(), p.values.begin(), p.values.end());
    out.counts.insert(out.counts.end(), p.counts.begin(), p.counts.end());
    out.numbers.insert(out.numbers.end(), p.numbers.begin(), p.numbers.end());
    out.error = p.error;
  }
  return out;
}

}  // namespace hermite
