#include "pipeline/progress.h"

#include <unistd.h>

#include <algorithm>

namespace hairfit {

namespace {

constexpr int kBarWidth = 30;
constexpr double kRedrawSeconds = 0.1;

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

ProgressStyle progress_style_for(std::FILE* stream, bool quiet) {
  if (quiet) return ProgressStyle::quiet;
  return isatty(fileno(stream)) ? ProgressStyle::bar : ProgressStyle::lines;
}

void ProgressReporter::stage_begins(const std::string& stage, std::size_t items) {
  const std::lock_guard<std::mutex> lock(mutex_);
  stage_ = stage;
  items_ = items;
  shown_ = 0;
  quarters_shown_ = 0;
  bar_drawn_ = false;
  start_ = last_draw_ = std::chrono::steady_clock::now();
  if (style_ == ProgressStyle::lines) {
    if (items) std::fprintf(stream_, "%s: started (%zu items)\n", stage.c_str(), items);
    else std::fprintf(stream_, "%s: started\n", stage.c_str());
    std::fflush(stream_);
  }
}

void ProgressReporter::items_done(std::size_t done) {
  if (style_ == ProgressStyle::quiet || items_ == 0) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  if (done <= shown_) return;  // threads may report out of order
  shown_ = std::min(done, items_);
  if (style_ == ProgressStyle::lines) {
    const int quarters = static_cast<int>(4 * shown_ / items_);
    if (quarters > quarters_shown_ && quarters < 4) {
      quarters_shown_ = quarters;
      std::fprintf(stream_, "%s: %d%% (%zu/%zu)\n", stage_.c_str(), 25 * quarters, shown_, items_);
      std::fflush(stream_);
    }
    return;
  }
  if (seconds_since(last_draw_) < kRedrawSeconds && shown_ < items_) return;
  last_draw_ = std::chrono::steady_clock::now();
  draw_bar(shown_, seconds_since(start_));
}

void ProgressReporter::draw_bar(std::size_t done, double elapsed) {
  const int filled = static_cast<int>(kBarWidth * done / items_);
  const double rate = elapsed > 0 ? done / elapsed : 0.0;
  char left[32] = "";
  if (rate > 0 && done < items_) std::snprintf(left, sizeof left, ", %.0f s left", (items_ - done) / rate);
  std::fprintf(stream_, "\r%-10s [%s%s] %zu/%zu, %.0f/s%s\x1b[K", stage_.c_str(), std::string(filled, '#').c_str(),
               std::string(kBarWidth - filled, '.').c_str(), done, items_, rate, left);
  std::fflush(stream_);
  bar_drawn_ = true;
}

void ProgressReporter::stage_ends(const std::string& stage, const std::string& status, double seconds) {
  const std::lock_guard<std::mutex> lock(mutex_);
  items_ = 0;  // late callbacks draw nothing
  if (style_ == ProgressStyle::quiet) return;
  if (bar_drawn_) std::fprintf(stream_, "\r\x1b[K");
  bar_drawn_ = false;
  std::fprintf(stream_, "%s: %s in %.2f s\n", stage.c_str(), status.c_str(), seconds);
  std::fflush(stream_);
}

void ProgressReporter::note(const std::string& text) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (style_ == ProgressStyle::quiet) return;
  if (bar_drawn_) std::fprintf(stream_, "\r\x1b[K");
  std::fprintf(stream_, "%s\n", text.c_str());
  std::fflush(stream_);
}

}  // namespace hairfit
