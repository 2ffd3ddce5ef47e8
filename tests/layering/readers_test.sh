#!/usr/bin/env bash
# The reader check must pass on this tree, and on a small tree must name each
# planted reader that skips the reader policy while passing the policy's own
# implementation, marked readers, writers and readers named in comments.
set -euo pipefail
src=$1
check=$src/scripts/check-readers.sh
fail() { echo "readers_test: $*" >&2; exit 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mk() { mkdir -p "$(dirname "$tmp/$1")"; printf '%s\n' "${@:2}" >"$tmp/$1"; }

# A clean tree passes: the policy itself, marked readers, writers, comments.
mk firmware/platform/linux/regular_file.cpp \
  'const int fd = ::open(path, O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);'
mk host_sim/ok/readers.cpp \
  '#include <fstream>' \
  'std::ifstream in(p);  // reader policy: checked by io::check_regular_file above' \
  '  // reader policy: checked by io::read_regular_file above' \
  '  MatFile mat(Mat_Open(label.c_str(), MAT_ACC_RDONLY));' \
  'std::ofstream out(p);' \
  'const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);' \
  'const int fd = ::open(tmp.c_str(),' \
  '                      O_WRONLY | O_CREAT, 0644);' \
  'const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);' \
  '// Never std::ifstream here: a FIFO would block (see fopen(3)).' \
  'chip.open(name, gpiod::chip::OPEN_LOOKUP);' \
  'FILE* p = popen("gnuplot", "w");'
"$check" "$tmp" >/dev/null || fail "a clean tree was refused: $("$check" "$tmp" 2>&1)"

# One bad reader of each kind, and markers that do not count.
mk common/bad.hpp 'inline std::string slurp(const char* p) { std::ifstream f(p); return {}; }'
mk firmware/app/bad.cpp \
  'std::FILE* f = std::fopen(path.c_str(), "rb");' \
  'const auto n = std::filesystem::file_size(path);' \
  'auto t = toml::parse_file(path);'
mk host_sim/bad/readers.cpp \
  'const int fd = ::open(path.c_str(),' \
  '                      O_RDONLY | O_CLOEXEC);' \
  'int fd2 = open(path.c_str(), flags);' \
  'void* m = mmap(nullptr, n, PROT_READ, MAP_PRIVATE, fd, 0);' \
  'std::fstream both(path);  // reader policy:' \
  'MatFile mat(Mat_Open(label.c_str(), MAT_ACC_RDONLY));  // readers policy: a typo is no marker' \
  'std::basic_ifstream<char> in(path);' \
  'fs::copy_file(from, to);'
set +e
out=$("$check" "$tmp" 2>&1)
status=$?
set -e
((status == 1)) || fail "planted readers: expected exit 1, got $status"$'\n'"$out"
for expect in \
  'common/bad.hpp:1: inline std::string slurp' \
  'firmware/app/bad.cpp:1: std::FILE* f = std::fopen' \
  'firmware/app/bad.cpp:2: const auto n = std::filesystem::file_size' \
  'firmware/app/bad.cpp:3: auto t = toml::parse_file' \
  'host_sim/bad/readers.cpp:1: const int fd = ::open(path.c_str(),' \
  'host_sim/bad/readers.cpp:3: int fd2 = open(' \
  'host_sim/bad/readers.cpp:4: void* m = mmap(' \
  'host_sim/bad/readers.cpp:5: std::fstream both(path);' \
  'host_sim/bad/readers.cpp:6: MatFile mat(Mat_Open(' \
  'host_sim/bad/readers.cpp:7: std::basic_ifstream<char> in(path);' \
  'host_sim/bad/readers.cpp:8: fs::copy_file(from, to);' \
  '(open() without O_WRONLY or O_DIRECTORY reads:' \
  'readers: 11 reader(s) outside the reader policy'; do
  grep -qF -- "$expect" <<<"$out" || fail "missing in the report: $expect"$'\n'"$out"
done
reported=$(grep -cE '^[^ ].*:[0-9]+: ' <<<"$out" || true)
((reported == 11)) || fail "expected 11 readers reported, got $reported"$'\n'"$out"

# Last: this tree (fails while a reader outside the policy remains).
"$check" "$src" || fail "the source tree has readers outside the reader policy (lines above)"
echo "readers_test: 11 planted readers found, each named; clean readers, writers and comments passed; the tree passes"
