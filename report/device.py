"""The device a result set was measured on, for the top of the report: experiment.json's `device`
record (processor, Vulkan device and driver, Embree, threads, system) and the ray backend of the
runs (their parameter `rays`; Embree where a run does not name one), and the fraction of the
configured size the set was rendered at (`hybridlab run --scale`) where not all of it. A raster that ran on a
software Vulkan device (vulkan_device_type "cpu", e.g. Mesa's lavapipe) is flagged: its frame times
are not a GPU's; so is a GPU that runs graphics on few of its units (results.graphics_caveat)."""
import html

import results as rs

FIELDS = (("processor", ("cpu_model", "cpu_cores"), "%s (%s cores)"),
          ("Vulkan device", ("vulkan_device", "vulkan_device_type"), "%s (%s)"),
          ("Vulkan driver", ("vulkan_driver", "vulkan_api_version"), "%s, Vulkan %s"),
          ("Embree", ("embree_version",), "%s"),
          ("threads", ("tbb_threads", "lp_num_threads"), "TBB %s, lavapipe %s"),
          ("system", ("os",), "%s"),
          ("program", ("program_version",), "%s"))


def ray_backends(records):
    return sorted({str(r.get("parameters", {}).get("rays", "embree")) for r in records})


def lines(result_dir, records):
    """(label, text) pairs and a warning (or None)."""
    devices = rs.devices(result_dir, records)
    rows = [("ray backend", ", ".join(ray_backends(records)))]
    scale = rs.resolution_scale(result_dir)
    if scale != 1.0:
        rows.append(("size", "rendered at %g of the configured size (hybridlab run --scale %g)" % (scale, scale)))
    if len(devices) > 1:
        return [("devices", rs.device_line(result_dir, records))] + rows, (
            "The runs were measured on %d different devices: their times do not compare across them." % len(devices))
    device = devices[0]
    if not device:
        return [("device", "device not recorded")] + rows, None
    for label, keys, spec in FIELDS:
        if any(k in device for k in keys):
            rows.append((label, spec % tuple(device.get(k, "?") for k in keys)))
    warning = None
    if device.get("vulkan_device_type") == "cpu":
        warning = ("The raster ran on a software Vulkan device (%s): its frame times are a CPU's, not a GPU's, and the "
                   "rasterizing techniques' speed-ups are not what a GPU would give." % device.get("vulkan_device", "?"))
    warning = warning or rs.graphics_caveat(device)
    return rows, warning


def write(result_dir, records):
    """The device block as (HTML, Markdown lines); the HTML's warning is warning_html's, which the
    page shows at its top."""
    rows, warning = lines(result_dir, records)
    page = '<table class="device">' + "".join("<tr><th>%s</th><td>%s</td></tr>" % (html.escape(k), html.escape(v)) for k, v in rows) + "</table>"
    md = ["", "Measured on: " + "; ".join("%s: %s" % kv for kv in rows) + "."]
    if warning:
        md += ["", "**Warning:** " + warning]
    return page, md


def warning_html(result_dir, records):
    """The device's warning as a paragraph for the top of the page ("" without one)."""
    _, warning = lines(result_dir, records)
    return '<p class="warning">Warning: %s</p>' % html.escape(warning) if warning else ""
