#pragma once
// A camera's shutter as fractions of the frame interval (Camera::shutterOpen,
// shutterClose), judged the same way by everyone who reads one.
namespace tsr::sg {

// Opens and closes within the frame interval: 0 <= open <= close <= 1 (NaN fails).
inline bool shutterWithinFrame(float open, float close) { return open >= 0.0f && open <= close && close <= 1.0f; }

// Stays open over part of the interval (else an instant: nothing blurs).
inline bool shutterStaysOpen(float open, float close) { return close > open; }

}  // namespace tsr::sg
