#!/usr/bin/env python3
"""Every ray-generation shader's private memory (its Private and Function variables, from the
SPIR-V the build embeds) stays within a budget that NVIDIA's driver runs. Its ray-tracing stack
holds them, and above a bound the Vulkan API does not report the driver loses the device: on an
H200 with driver 580.159.04, device_whitted.rgen with a 48-entry ray stack (9756 bytes by this
count; vkGetRayTracingShaderGroupStackSizeKHR: 14624) lost it, with 32 entries (6684 bytes; 10016)
and with 66 small entries (5484 bytes; 11072) it ran. lavapipe runs any size, so only this count
catches a shader grown past the bound on a machine without such a GPU.

    ray_stack_budget_test.py SHADER_INC_DIR

SHADER_INC_DIR: the build's shaders/ folder (NAME.inc, the SPIR-V words as C initializers)."""
import pathlib
import sys

# Between the largest that ran (6752, device_heuristic_rt.rgen and device_ssr_fallback.rgen) and
# the smallest that did not (9756).
BUDGET_BYTES = 8000

OP_TYPE_BOOL, OP_TYPE_INT, OP_TYPE_FLOAT, OP_TYPE_VECTOR, OP_TYPE_MATRIX = 20, 21, 22, 23, 24
OP_TYPE_ARRAY, OP_TYPE_STRUCT, OP_TYPE_POINTER, OP_CONSTANT, OP_VARIABLE = 28, 30, 32, 43, 59
STORAGE_PRIVATE, STORAGE_FUNCTION = 6, 7


def spirv_words(inc):
    return [int(w, 0) for w in inc.read_text().replace("\n", " ").split(",") if w.strip()]


def private_bytes(words):
    """The bytes of every Private and Function variable, members packed without padding."""
    if not words or words[0] != 0x07230203:
        raise ValueError("not SPIR-V")
    types, constants, variables = {}, {}, []
    i = 5
    while i < len(words):
        opcode, count = words[i] & 0xFFFF, words[i] >> 16
        operands = words[i + 1:i + count]
        if opcode in (OP_TYPE_INT, OP_TYPE_FLOAT):
            types[operands[0]] = ("scalar", operands[1] // 8)
        elif opcode == OP_TYPE_BOOL:
            types[operands[0]] = ("scalar", 4)
        elif opcode in (OP_TYPE_VECTOR, OP_TYPE_MATRIX):
            types[operands[0]] = ("repeat", operands[1], operands[2])
        elif opcode == OP_TYPE_ARRAY:
            types[operands[0]] = ("array", operands[1], operands[2])
        elif opcode == OP_TYPE_STRUCT:
            types[operands[0]] = ("struct", operands[1:])
        elif opcode == OP_TYPE_POINTER:
            types[operands[0]] = ("pointer", operands[1], operands[2])
        elif opcode == OP_CONSTANT:
            constants[operands[1]] = operands[2]
        elif opcode == OP_VARIABLE:
            variables.append((operands[0], operands[2]))
        i += max(count, 1)

    def size(t):
        kind = types.get(t, ("other",))
        if kind[0] == "scalar":
            return kind[1]
        if kind[0] == "repeat":
            return size(kind[1]) * kind[2]
        if kind[0] == "array":
            return size(kind[1]) * constants[kind[2]]
        if kind[0] == "struct":
            return sum(size(m) for m in kind[1])
        return 0

    return sum(size(types[pointer][2]) for pointer, storage in variables if storage in (STORAGE_PRIVATE, STORAGE_FUNCTION))


def main():
    folder = pathlib.Path(sys.argv[1])
    shaders = sorted(folder.glob("*.rgen.inc"))
    if not shaders:
        print(f"no ray-generation shaders in {folder}")
        return 1
    counts = {inc.name[:-4]: private_bytes(spirv_words(inc)) for inc in shaders}
    for name, n in counts.items():
        print(f"{name:32s} {n:6d} bytes")
    over = [name for name, n in counts.items() if n > BUDGET_BYTES]
    # The count itself: the shaders that keep a ray stack have one, the replay none.
    if counts.get("device_whitted.rgen", 0) < 1000:
        print("FAILED: device_whitted.rgen's ray stack was not counted")
        return 1
    for name in over:
        print(f"FAILED: {name} holds more than {BUDGET_BYTES} bytes of private memory, past what NVIDIA's driver ran")
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main())
