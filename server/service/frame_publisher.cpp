#include "service/frame_publisher.h"

#include <algorithm>
#include <cmath>

#include "assembly/film_exr.h"

namespace glint {
namespace {

// Each pixel's camera samples over the most any pixel has, as a linear grey PNG.
std::vector<uint8_t> samples_png(const Film& film, uint64_t& most) {
    most = 1;
    for (const PixelSums& px : film.pixels()) most = std::max(most, px.count);
    Image grey(film.width(), film.height());
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x)  // gamma 2.2 encoding undone, so grey is linear in count
            grey.set(x, y, Rgb{std::pow(double(film.pixel(x, y).count) / double(most), 2.2)});
    return encode_png(grey, Encoding::gamma22);
}

// The frame's image and its PNG.
JobFrame picture(Image image, Encoding encoding) {
    JobFrame frame;
    frame.image = std::make_shared<const Image>(std::move(image));
    frame.png = std::make_shared<const std::vector<uint8_t>>(encode_png(*frame.image, encoding));
    return frame;
}

}  // namespace

void FramePublisher::publish(JobState state, const Progress& progress) const {
    const Film& film = render_.film();
    JobFrame frame = picture(film.mean(), render_.settings().encoding);
    if (std::vector<ExrLayer> layers = film_layers(film); !layers.empty())
        frame.layers = std::make_shared<const std::vector<ExrLayer>>(std::move(layers));
    frame.halves = std::make_shared<const HalfBuffers>(half_buffers(film));
    if (render_.settings().adaptive.on())
        frame.samples_png = std::make_shared<const std::vector<uint8_t>>(samples_png(film, frame.samples_max));
    status_.publish(std::move(frame), state, progress);
}

void FramePublisher::publish_preview(const Image& preview) const {
    JobFrame frame = picture(preview, render_.settings().encoding);
    frame.preview = true;
    status_.publish(std::move(frame), JobState::running, status_.snapshot().progress);
}

void FramePublisher::publish_restored(const Film* film, JobState state, const Progress& progress) const {
    JobFrame frame;
    if (film) {
        frame = picture(film->mean(), render_.settings().encoding);
        frame.halves = std::make_shared<const HalfBuffers>(half_buffers(*film));
    }
    status_.publish(std::move(frame), state, progress);
}

}  // namespace glint
