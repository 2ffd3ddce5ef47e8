#!/usr/bin/env bash
# Checks that every file the programs read goes through the reader policy
# (README, "Inputs are checked before any folder is made"): a regular file,
# opened without blocking, within a stated size, or a clear error. The one
# implementation is firmware/platform/linux/regular_file.cpp
# (posix::read_regular_file; io::read_regular_file and io::check_regular_file
# on the host call it).
#
# Any other way of opening a file for reading in common/, firmware/ and
# host_sim/ is refused:
#   std::ifstream / std::fstream (and their basic_ forms), fopen, freopen,
#   open() / openat() unless the call says O_WRONLY or O_DIRECTORY (a writer,
#   or a folder opened to fsync it), toml::parse_file, Mat_Open, mmap,
#   std::filesystem::file_size, std::filesystem::copy_file,
# unless the line, or a comment line right above it, carries a marker that
# says which check of the policy covers it:
#   // reader policy: checked by io::read_regular_file above
# Writers (std::ofstream, open() with O_WRONLY) are not readers. Comments are
# not code: a reader named in a comment is not a reader.
#
# Usage: check-readers.sh [SOURCE_ROOT]   (default: the repository holding this script)
# Prints one line per reader outside the policy (file:line: the code, and the
# rule) and exits 1 if there is any; exits 0 with a one-line count otherwise.
set -euo pipefail
root=${1:-$(cd "$(dirname "$0")/.." && pwd)}
cd "$root"

# The policy's own implementation.
policy_files='firmware/platform/linux/regular_file.cpp'

files=()
for dir in common firmware host_sim; do
  [[ -d $dir ]] || continue
  while IFS= read -r f; do files+=("$f"); done < <(
    find "$dir" -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' -o -name '*.cc' -o -name '*.c' \) | sort)
done
if ((${#files[@]} == 0)); then
  echo "readers: no sources under $root (common, firmware, host_sim)" >&2
  exit 1
fi

status=0
awk -v policy="$policy_files" '
  function code_of(line) {  # the line without its // comment
    sub(/\/\/.*$/, "", line)
    return line
  }
  function marked(i) {
    if (raw[i] ~ /\/\/[[:space:]]*reader policy:[[:space:]]*[^[:space:]]/) return 1
    return i > 1 && raw[i - 1] ~ /^[[:space:]]*\/\/[[:space:]]*reader policy:[[:space:]]*[^[:space:]]/
  }
  function report(i, what) {
    text = raw[i]
    sub(/^[[:space:]]+/, "", text)
    printf "%s:%d: %s\n    (%s: read it through posix::read_regular_file or io::read_regular_file, " \
           "or mark the line \"// reader policy: <which check covers it>\")\n", file, i, text, what
    found++
  }
  function check_file(   i, c, call, j) {
    for (i = 1; i <= n; i++) {
      c = code_of(raw[i])
      if (c ~ /^[[:space:]]*#[[:space:]]*include/) continue
      what = ""
      if (c ~ /(^|[^[:alnum:]_])(basic_)?i?fstream([^[:alnum:]_]|$)/) what = "a std::ifstream or std::fstream reads"
      else if (c ~ /(^|[^[:alnum:]_])(fopen|freopen|fdopen)[[:space:]]*\(/) what = "fopen reads"
      else if (c ~ /toml::parse_file[[:space:]]*\(/) what = "toml::parse_file reads"
      else if (c ~ /(^|[^[:alnum:]_])Mat_Open[[:space:]]*\(/) what = "Mat_Open reads"
      else if (c ~ /(^|[^[:alnum:]_])mmap[[:space:]]*\(/) what = "mmap reads"
      else if (c ~ /(^|[^[:alnum:]_])file_size[[:space:]]*\(/) what = "std::filesystem::file_size sizes a file to read"
      else if (c ~ /(^|[^[:alnum:]_])copy_file[[:space:]]*\(/) what = "std::filesystem::copy_file reads"
      else if (c ~ /(^|[^[:alnum:]_.>])(::)?open(at)?[[:space:]]*\(/) {
        # The call with its arguments: this line and up to two more, to the first ";".
        call = c
        for (j = i + 1; j <= n && j <= i + 2 && call !~ /;/; j++) call = call " " code_of(raw[j])
        if (call !~ /O_WRONLY|O_DIRECTORY/) what = "open() without O_WRONLY or O_DIRECTORY reads"
      }
      if (what != "" && !marked(i)) report(i, what)
    }
  }
  FNR == 1 && NR > 1 { if (!(prev in skip)) check_file() }
  FNR == 1 { file = FILENAME; prev = FILENAME; n = 0 }
  { raw[++n] = $0 }
  END {
    if (n > 0 && !(prev in skip)) check_file()
    if (found) { printf "readers: %d reader(s) outside the reader policy\n", found > "/dev/stderr"; exit 1 }
    printf "readers: ok (common, firmware, host_sim: every reader goes through the reader policy or says which check covers it)\n"
  }
  BEGIN { np = split(policy, p, " "); for (k = 1; k <= np; k++) skip[p[k]] = 1 }
' "${files[@]}" || status=$?
exit "$status"
