"""MATLAB level-5 .mat files built element by element (the format: a 128-byte header, then tagged
elements, each a type and a byte count), for files no MATLAB writer makes: damaged ones whose
declared sizes libmatio would trust with an allocation before it notices that the file does not
hold them. CRAFTED maps a name to (bytes, what spdfit's message says); each drives a different path
through libmatio (see the comments). `python3 level5_mat.py DIR` writes them into DIR (as .mat
files: fuzzing seeds).

Every huge size here is one libmatio reads from a place spdfit's check of the structure would not
otherwise look at, or reads differently from the tags: a name element that is not miINT8, a flags
element of 16 bytes, a struct's field name length as a full tag, the data element of a char array
or the index elements of a sparse one (libmatio reads those of small compressed struct fields and
cells while it lists the variables), a function handle's elements."""
import struct
import sys
import zlib

MI_INT8, MI_UINT8, MI_INT32, MI_UINT32, MI_DOUBLE = 1, 2, 5, 6, 9
MI_MATRIX, MI_COMPRESSED, MI_UTF8 = 14, 15, 16
CELL, STRUCT, CHAR, SPARSE, DOUBLE, FUNCTION, OPAQUE = 1, 2, 4, 5, 6, 16, 17
COMPLEX = 0x800
HUGE = 0xFFFFFFF0  # about 4 GB, as a byte count


def header():
    text = b"MATLAB 5.0 MAT-file, crafted by tests/support/level5_mat.py"
    return text.ljust(116, b" ") + b"\0" * 8 + struct.pack("<H", 0x0100) + b"IM"


def pad(data):
    return data + b"\0" * (-len(data) % 8)


def tag(kind, count):
    return struct.pack("<II", kind, count)


def element(kind, data, count=None):
    """A full element: tag (with `count`, default the data's length) and data padded to 8 bytes."""
    return tag(kind, len(data) if count is None else count) + pad(data)


def small(kind, data):
    """A small element: type and size in one word, up to 4 bytes of data in the next."""
    assert len(data) <= 4
    return struct.pack("<HH", kind, len(data)) + data.ljust(4, b"\0")


def flags(array_class, nzmax=0, extra=b""):
    return element(MI_UINT32, struct.pack("<II", array_class, nzmax) + extra)


def dims(*shape):
    return element(MI_INT32, struct.pack(f"<{len(shape)}i", *shape))


def name(text):
    data = text.encode()
    return small(MI_INT8, data) if 0 < len(data) <= 4 else element(MI_INT8, data)


def matrix(content):
    return tag(MI_MATRIX, len(content)) + content


def double_array(label, rows, cols, values=None):
    values = [float(k + 1) for k in range(rows * cols)] if values is None else values
    data = element(MI_DOUBLE, struct.pack(f"<{len(values)}d", *values))
    return matrix(flags(DOUBLE) + dims(rows, cols) + name(label) + data)


def compressed(content):
    packed = zlib.compress(content)
    return tag(MI_COMPRESSED, len(packed)) + packed


def field_name_length(length=32):
    return small(MI_INT32, struct.pack("<i", length))


def struct_names(*names, length=32):
    return field_name_length(length) + element(MI_INT8, b"".join(n.encode().ljust(length, b"\0") for n in names))


def mat_file(*elements):
    return header() + b"".join(elements)


# A struct header libmatio would read from bytes spdfit's check skips: a field name length of 1,
# then field names of HUGE bytes (libmatio allocates them before reading).
HIDDEN_STRUCT = field_name_length(1) + tag(MI_INT8, HUGE)

CRAFTED = {
    # The top-level name element is miUINT8, not miINT8: libmatio reads no name and takes its
    # bytes for the struct's field names (HUGE bytes).
    "name_not_int8.mat": (
        mat_file(matrix(flags(STRUCT) + dims(1, 1) + element(MI_UINT8, HIDDEN_STRUCT) + struct_names())),
        "the name of an array is an element of type 2, not miINT8"),
    # A 16-byte flags element: libmatio reads the dimensions' tag at a fixed place, inside the
    # flags, here declaring HUGE bytes of dimensions (it allocates twice that).
    "flags_of_16_bytes.mat": (
        mat_file(matrix(element(MI_UINT32, struct.pack("<IIII", DOUBLE, 0, MI_INT32, HUGE)) + dims(1, 1)
                        + name("x") + element(MI_DOUBLE, struct.pack("<d", 1.0)))),
        "an array's flags are not one miUINT32 element of 8 bytes"),
    # The field name length as a full miINT32 tag: libmatio takes its byte count (4) for the
    # length and the value's 8 bytes for the names' tag (miINT8, HUGE bytes).
    "field_name_length_full_tag.mat": (
        mat_file(matrix(flags(STRUCT) + dims(1, 1) + name("s") + tag(MI_INT32, 4) + struct.pack("<iI", 1, HUGE)
                        + element(MI_INT8, b""))),
        "a struct without its field name length"),
    # A struct field named in its own element (MATLAB leaves fields unnamed): libmatio reads 8
    # bytes of it and takes the rest for the field's own struct header.
    "field_with_a_name.mat": (
        mat_file(matrix(flags(STRUCT) + dims(1, 1) + name("s") + struct_names("f")
                        + matrix(flags(STRUCT) + dims(1, 1) + element(MI_INT8, HIDDEN_STRUCT) + struct_names()))),
        "a struct field with a name of its own"),
    # A char array in a compressed struct: libmatio reads small fields while listing the
    # variables and allocates the byte count of the char data's tag (HUGE).
    "compressed_char_field.mat": (
        mat_file(compressed(matrix(flags(STRUCT) + dims(1, 1) + name("s") + struct_names("c")
                                   + matrix(flags(CHAR) + dims(1, 1) + name("") + tag(MI_UTF8, HUGE) + b"a" * 8)))),
        "an element declares 4294967280 bytes, more than it holds"),
    # A sparse matrix in a compressed cell array: the row indices' tag declares HUGE bytes.
    "compressed_sparse_cell.mat": (
        mat_file(compressed(matrix(flags(CELL) + dims(1, 1) + name("c")
                                   + matrix(flags(SPARSE, nzmax=1) + dims(1, 1) + name("") + tag(MI_INT32, HUGE)
                                            + b"\0" * 24)))),
        "an element declares 4294967280 bytes, more than it holds"),
    # Its values' tag declares HUGE bytes (the indices are whole).
    "compressed_sparse_values.mat": (
        mat_file(compressed(matrix(flags(CELL) + dims(1, 1) + name("c")
                                   + matrix(flags(SPARSE, nzmax=1) + dims(1, 1) + name("")
                                            + element(MI_INT32, struct.pack("<i", 0))
                                            + element(MI_INT32, struct.pack("<ii", 0, 1))
                                            + tag(MI_DOUBLE, HUGE) + b"\0" * 8)))),
        "an element declares 4294967280 bytes, more than it holds"),
    # A function handle: libmatio reads its contents as variables; here a compressed 65536 x 65536
    # cell array (a 32 GB array of pointers).
    "function_handle_of_a_huge_cell.mat": (
        mat_file(matrix(flags(FUNCTION) + dims(1, 1) + name("f")
                        + compressed(matrix(flags(CELL) + dims(65536, 65536) + name("c"))))),
        "a cell array declares 4294967296 cells in 0 bytes"),
    # An opaque object (MATLAB's string, table, ... classes) written uncompressed, its first
    # element an miINT32 that declares HUGE bytes: libmatio reads it as the dimensions.
    "opaque_dimensions.mat": (
        mat_file(matrix(flags(OPAQUE) + tag(MI_INT32, HUGE) + b"\0" * 16)),
        "an element declares 4294967280 bytes, more than it holds"),
    # An opaque object as MATLAB writes it, flags then its name, here an 8-byte one: libmatio
    # takes the name's tag for the dimensions' and reads the name's bytes as the name's tag, here
    # declaring HUGE bytes (found by fuzz_mat).
    "opaque_name_read_as_a_tag.mat": (
        mat_file(matrix(flags(OPAQUE) + element(MI_INT8, tag(MI_INT8, HUGE)) + b"\0" * 8)),
        "an element declares 4294967280 bytes, more than it holds"),
    # A cell array declaring 2 cells whose first fills it: libmatio reads the second from the
    # bytes after it.
    "cell_missing_a_cell.mat": (
        mat_file(matrix(flags(CELL) + dims(1, 2) + name("c") + double_array("", 1, 1))),
        "a cell array declares 2 cells and holds 1"),
    # A compressed element whose deflate stream goes on past its byte count.
    "compressed_stream_longer.mat": (
        (lambda packed: mat_file(tag(MI_COMPRESSED, len(packed) - 6) + packed))(
            zlib.compress(double_array("x", 1, 1))),
        "a compressed element does not inflate"),
}

# A MATLAB string variable as MATLAB writes it (an opaque object: flags, name, "MCOS", class
# name, then its data) next to a numeric one: the numeric one reads.
MATLAB_STRING_AND_MATRIX = mat_file(
    matrix(flags(OPAQUE) + name("label") + small(MI_INT8, b"MCOS") + name("string")
           + matrix(flags(13) + dims(6, 1) + name("") + element(MI_UINT32, struct.pack("<6I", 0xDD000000, 2, 1, 1, 1, 1)))),
    double_array("X", 2, 2, [2.0, 0.5, 0.5, 1.0]))


if __name__ == "__main__":
    import pathlib
    out = pathlib.Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    for file, (data, _) in CRAFTED.items():
        (out / file).write_bytes(data)
    (out / "matlab_string_and_matrix.mat").write_bytes(MATLAB_STRING_AND_MATRIX)
