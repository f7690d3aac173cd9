#pragma once
#include "image/image.h"

namespace vkdr {

// How far a render of a view the fit never saw is from its target, against how far a
// render of the true scene is: both rendered with the same samples (the same seed and
// spp), so that their noise largely cancels in the comparison and what is left is the
// fit's error.
struct HeldOutError {
    // sqrt(mean squared difference to the target) over the target's mean, every pixel and
    // channel: the render's error as a fraction of the image's brightness.
    double relativeRmse = 0.0;
    // The same for the true scene's render: the noise floor, what a perfect fit reaches.
    double floorRelativeRmse = 0.0;
    // The mean over pixels of (the render's squared difference - the true render's), in
    // standard errors of that mean: within about 2 the fit is indistinguishable from the
    // truth at this noise level.
    double excessInStandardErrors = 0.0;
};

// The mean of every pixel and channel of a held-out view's target, which its errors are
// relative to: a view whose target's mean is not above 0 cannot be held out.
double targetMean(const Image& target);

// `render` and `trueRender` of one view, against `target`; all three the same size.
// Throws vkdr::Error when they are not, or when the target is black.
HeldOutError heldOutError(const Image& render, const Image& trueRender, const Image& target);

}  // namespace vkdr
