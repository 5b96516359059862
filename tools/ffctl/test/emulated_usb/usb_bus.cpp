#include "usb_bus.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>

namespace ff::ffctl::emulated_usb {

UsbBus UsbBus::load() {
  const char* folder = std::getenv("FF_EMULATED_USB");
  return folder ? load_from(folder) : UsbBus();
}

UsbBus UsbBus::load_from(const std::string& folder) {
  UsbBus bus;
  bus.folder_ = folder;
  std::ifstream in(bus.folder_ + "/bus");
  for (std::string line; std::getline(in, line);) {
    const size_t eq = line.find('=');
    if (eq != std::string::npos) bus.values_[line.substr(0, eq)] = line.substr(eq + 1);
  }
  return bus;
}

void UsbBus::save() const {
  if (folder_.empty()) return;
  const std::string path = folder_ + "/bus", partial = path + ".partial";
  {
    std::ofstream out(partial);
    for (const auto& [key, value] : values_) out << key << '=' << value << '\n';
  }
  std::rename(partial.c_str(), path.c_str());
}

std::string UsbBus::get(const std::string& key, const std::string& fallback) const {
  const auto it = values_.find(key);
  return it == values_.end() ? fallback : it->second;
}

long UsbBus::get_long(const std::string& key, long fallback) const {
  const std::string v = get(key);
  return v.empty() ? fallback : std::strtol(v.c_str(), nullptr, 10);
}

std::string UsbBus::device_now() const {
  if (wall_ms() < get_long("appears_at_ms", 0)) return "absent";
  return get("device", "absent");
}

void UsbBus::plug(const std::string& device, long delay_ms) {
  set("device", device);
  set("appears_at_ms", wall_ms() + delay_ms);
  set("erased", 0L);
  set("writes", 0L);
}

void UsbBus::event(const std::string& line) const {
  if (folder_.empty()) return;
  std::ofstream(folder_ + "/events", std::ios::app) << line << '\n';
}

long UsbBus::wall_ms() {
  return static_cast<long>(std::chrono::duration_cast<std::chrono::milliseconds>(
                               std::chrono::system_clock::now().time_since_epoch())
                               .count());
}

}  // namespace ff::ffctl::emulated_usb
