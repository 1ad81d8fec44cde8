#pragma once
// The data lines of a text file of numbers (point files, probe files): a line reader, the
// numbers of one line, and all lines parsed in parallel chunks. Blank lines and lines whose first
// non-blank character is '#' are skipped; a UTF-8 byte-order mark at the start and a trailing
// '\r' (CRLF) are ignored. A token that is not a finite number is an InputError "PATH:LINE: ...".

#include <exception>
#include <string>
#include <string_view>
#include <vector>

namespace hermite {

// Iterates over the data lines of `text`, numbering them from linesBefore + 1 (a chunk of a file
// starting after linesBefore line ends; 0: the whole file, whose byte-order mark is skipped).
class LineReader {
 public:
  explicit LineReader(std::string_view text, long linesBefore = 0);
  // False at the end of the text; otherwise `line` holds the next data line and `number` its
  // 1-based line number in the file.
  bool next(std::string_view& line, long& number);

 private:
  const char* p_;
  const char* end_;
  long lineNumber_;
};

// Parses the blank-separated numbers of one line into `values` (at most `capacity` are stored)
// and returns how many there are. A token that is not a finite number throws "path:LINE: ...".
int parseNumbers(std::string_view line, double* values, int capacity, const std::string& path, long lineNumber);

// Every data line's numbers, in file order: as a LineReader + parseNumbers loop reads them, up to
// the first line that does not parse.
struct NumberLines {
  std::vector<double> values;  // `capacity` per line (unused slots 0)
  std::vector<int> counts;     // how many numbers each line has (may exceed capacity)
  std::vector<long> numbers;   // each line's 1-based number in the file
  // The InputError of the first line that does not parse (it follows the lines above), or null.
  std::exception_ptr error;
};

// The text in chunks of whole lines parsed on the OpenMP threads (a 200 000-line point file took
// 0.05 s on one core: docs/performance.md, "Serial stretches of mesh"); the result and the error
// are the serial loop's.
NumberLines parseNumberLines(std::string_view text, int capacity, const std::string& path);

}  // namespace hermite
