#pragma once
// The Embree device behind one small RAII wrapper (STYLE.md §5). The error callback is set when
// the device is made and turns every Embree error into owsim::Error at the next check().
// No module other than engine/ includes rtcore.h.
#include <embree3/rtcore.h>

#include <string>

namespace owsim {

class EmbreeDevice {
 public:
  // `config` is Embree's device configuration string (e.g. "threads=1"); empty = defaults.
  explicit EmbreeDevice(const std::string& config = "");
  ~EmbreeDevice();
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;

  [[nodiscard]] RTCDevice get() const { return device_; }
  // Throws owsim::Error if Embree reported an error since the last check.
  void check(const char* during) const;

 private:
  RTCDevice device_ = nullptr;
  std::string last_message_;  // written by Embree's error callback
};

}  // namespace owsim
