"""Independent reference numbers for tests/metrics/test_metrics_skimage.cpp.

Usage: python3 metrics_reference.py DIR

DIR holds, for each image pair NAME, the files NAME.test.npy and NAME.reference.npy (float32,
height x width x 3, display sRGB in [0, 1], exactly the values the C++ metrics read) and
NAME.ssim_map.npy (the C++ luma SSIM map, float32). For each pair this prints one JSON line with
scikit-image's SSIM (on the Rec. 709 luma of the sRGB values, and per channel), the largest
difference between scikit-image's SSIM map and the C++ one, and numpy's RMSE and scikit-image's
PSNR of the R, G, B values. Exits with status 3 when numpy or scikit-image is missing.
"""
import json
import pathlib
import sys

try:
    import numpy as np
    from skimage.metrics import peak_signal_noise_ratio, structural_similarity
except ImportError as error:
    print(f"metrics_reference.py: {error}", file=sys.stderr)
    sys.exit(3)  # the test tries another python3, or skips


def ssim(a, b, **kwargs):
    # Wang et al. 2004, as the scikit-image documentation says to match it.
    return structural_similarity(a, b, gaussian_weights=True, sigma=1.5, use_sample_covariance=False,
                                 data_range=1.0, **kwargs)


def main(folder):
    rec709 = np.array([0.2126, 0.7152, 0.0722])
    for test_path in sorted(pathlib.Path(folder).glob("*.test.npy")):
        name = test_path.name[:-len(".test.npy")]
        test = np.load(test_path).astype(np.float64)
        reference = np.load(test_path.with_name(name + ".reference.npy")).astype(np.float64)
        ours_map = np.load(test_path.with_name(name + ".ssim_map.npy")).astype(np.float64)
        luma_ssim, luma_map = ssim(test @ rec709, reference @ rec709, full=True)
        print(json.dumps({
            "name": name,
            "ssim_luma": float(luma_ssim),
            "ssim_rgb": float(ssim(test, reference, channel_axis=2)),
            "ssim_map_max_abs_diff": float(np.max(np.abs(luma_map - ours_map))),
            "rmse": float(np.sqrt(np.mean((test - reference) ** 2))),
            "psnr": float(peak_signal_noise_ratio(reference, test, data_range=1.0)),
        }))


if __name__ == "__main__":
    main(sys.argv[1])
