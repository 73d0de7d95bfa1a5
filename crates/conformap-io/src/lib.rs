//! Mesh file I/O for conformap: OBJ and glTF/GLB readers and writers with errors that name the file and line.
