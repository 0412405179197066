// Video files of frame sequences: the frames are piped as raw RGBA to the ffmpeg command line,
// which encodes H.264 (yuv420p, odd sizes padded by a pixel) into the container the file's
// extension names (.mp4, .mkv, ...).
#pragma once

#include <string>

#include "gvdp/base/image.h"

namespace gvdp::detail {

// The full path of `program` found on $PATH, or "" when it is not there.
std::string findOnPath(const std::string& program);

class VideoWriter {
 public:
  // Starts ffmpeg. Throws InputError when ffmpeg is not on the PATH.
  VideoWriter(const std::string& path, int width, int height, int fps);
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;
  ~VideoWriter();  // stops ffmpeg if close() was not called

  // The next frame (width x height). Throws Error when ffmpeg has stopped taking frames.
  void add(const Image& image);
  // Ends the stream and waits for ffmpeg; throws Error if it failed. Returns the frames written.
  int close();

 private:
  std::string path_;
  int width_, height_, frames_ = 0;
  int pipe_ = -1;  // ffmpeg's stdin
  int pid_ = -1;
};

}  // namespace gvdp::detail
