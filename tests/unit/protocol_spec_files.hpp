#pragma once
// Readers of the protocol's two documents, for the tests that hold the code to
// them: mrd.dbc (messages and Intel signals, decoded the way a CAN tool does)
// and the "Example frames" table of CAN_PROTOCOL.md.

#include <array>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace mrd::protocol::spec_files {

struct DbcSignal {
  std::string name;
  int start_bit = 0;
  int length = 0;
  bool is_signed = false;
  double factor = 1.0;
};

struct DbcMessage {
  std::uint32_t id = 0;
  std::string name;
  int dlc = 0;
  std::vector<DbcSignal> signals;
};

/// The BO_ and SG_ lines of `dir`/mrd.dbc, by message name.
inline std::map<std::string, DbcMessage> read_dbc(const std::string& dir) {
  std::ifstream in(dir + "/mrd.dbc");
  const std::regex bo(R"(^BO_ (\d+) (\w+): (\d+) \w+)");
  const std::regex sg(R"(^ SG_ (\w+) : (\d+)\|(\d+)@1([+-]) \(([^,]+),([^)]+)\))");
  std::map<std::string, DbcMessage> out;
  DbcMessage* cur = nullptr;
  std::string line;
  std::smatch m;
  while (std::getline(in, line)) {
    if (std::regex_search(line, m, bo)) {
      DbcMessage msg;
      msg.id = static_cast<std::uint32_t>(std::stoul(m[1]));
      msg.name = m[2];
      msg.dlc = std::stoi(m[3]);
      cur = &(out[msg.name] = msg);
    } else if (cur && std::regex_search(line, m, sg)) {
      cur->signals.push_back({m[1], std::stoi(m[2]), std::stoi(m[3]), m[4] == "-", std::stod(m[5])});
    }
  }
  return out;
}

/// Intel (little-endian) signal extraction as a DBC tool does it.
inline double dbc_value(const DbcSignal& s, const std::array<std::uint8_t, 8>& d) {
  std::uint64_t word = 0;
  for (int i = 7; i >= 0; --i) word = (word << 8) | d[i];
  std::uint64_t raw = (word >> s.start_bit) & ((s.length == 64) ? ~0ull : ((1ull << s.length) - 1));
  std::int64_t v = static_cast<std::int64_t>(raw);
  if (s.is_signed && (raw >> (s.length - 1)) & 1u) v -= static_cast<std::int64_t>(1ull << s.length);
  return static_cast<double>(v) * s.factor;
}

struct SpecExample {
  std::uint32_t id = 0;
  std::array<std::uint8_t, 8> data{};
};

inline std::string trim_cell(const std::string& s) {
  const auto b = s.find_first_not_of(" `");
  const auto e = s.find_last_not_of(" `");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

/// Rows "| n | message | values | 0xID | `B0 .. B7` |" of the "Example frames" section of `dir`/CAN_PROTOCOL.md.
inline std::map<int, SpecExample> read_spec_examples(const std::string& dir) {
  std::ifstream in(dir + "/CAN_PROTOCOL.md");
  std::map<int, SpecExample> out;
  std::string line;
  bool in_section = false;
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) == 0) in_section = line == "## Example frames";
    if (!in_section || line.size() < 2 || line[0] != '|') continue;
    std::vector<std::string> cells;
    std::stringstream ss(line.substr(1));
    std::string cell;
    while (std::getline(ss, cell, '|')) cells.push_back(trim_cell(cell));
    if (cells.size() < 5 || cells[0].empty() || !std::isdigit(static_cast<unsigned char>(cells[0][0]))) continue;
    SpecExample ex;
    ex.id = static_cast<std::uint32_t>(std::stoul(cells[3], nullptr, 16));
    std::stringstream bytes(cells[4]);
    for (auto& b : ex.data) {
      std::string hex;
      bytes >> hex;
      b = static_cast<std::uint8_t>(std::stoul(hex, nullptr, 16));
    }
    out[std::stoi(cells[0])] = ex;
  }
  return out;
}

}  // namespace mrd::protocol::spec_files
