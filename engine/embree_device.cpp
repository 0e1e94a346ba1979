#include "engine/embree_device.hpp"

#include "geometry/error.hpp"

namespace owsim {
namespace {

// Keeps Embree's own words for check(); Embree keeps the code itself (rtcGetDeviceError).
void on_embree_error(void* user, RTCError /*code*/, const char* message) {
  *static_cast<std::string*>(user) = message != nullptr ? message : "";
}

}  // namespace

EmbreeDevice::EmbreeDevice(const std::string& config)
    : device_(rtcNewDevice(config.empty() ? nullptr : config.c_str())) {
  if (device_ == nullptr) {
    throw Error("Embree: cannot create a device (" + std::to_string(rtcGetDeviceError(nullptr)) +
                ")");
  }
  rtcSetDeviceErrorFunction(device_, on_embree_error, &last_message_);
}

EmbreeDevice::~EmbreeDevice() { rtcReleaseDevice(device_); }

void EmbreeDevice::check(const char* during) const {
  const RTCError code = rtcGetDeviceError(device_);
  if (code != RTC_ERROR_NONE) {
    throw Error(std::string("Embree error ") + std::to_string(code) + " during " + during + ": " +
                last_message_);
  }
}

}  // namespace owsim
