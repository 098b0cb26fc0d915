#include <deal.II/base/exceptions.h>

#include <bsmpm/io/point_output.h>

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>

namespace bsmpm
{
  namespace
  {
    int
    zlib_level(const DataOutBase::VtkFlags::ZlibCompressionLevel level)
    {
      switch (level)
        {
          case DataOutBase::VtkFlags::no_compression:
            return Z_NO_COMPRESSION;
          case DataOutBase::VtkFlags::best_speed:
            return Z_BEST_SPEED;
          case DataOutBase::VtkFlags::best_compression:
            return Z_BEST_COMPRESSION;
          default:
            return Z_DEFAULT_COMPRESSION;
        }
    }



    /** Writes @p n bytes at @p data in base64 (padded, no line breaks), a
     * piece at a time. */
    void
    write_base64(std::ostream &out, const unsigned char *data, std::size_t n)
    {
      static constexpr char digits[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
      std::array<char, 4 * 4096> text;
      while (n > 0)
        {
          const std::size_t bytes = std::min<std::size_t>(n, 3 * 4096);
          std::size_t       t     = 0;
          for (std::size_t i = 0; i < bytes; i += 3, t += 4)
            {
              const unsigned int b0 = data[i];
              const unsigned int b1 = i + 1 < bytes ? data[i + 1] : 0;
              const unsigned int b2 = i + 2 < bytes ? data[i + 2] : 0;
              text[t]               = digits[b0 >> 2];
              text[t + 1]           = digits[((b0 & 3) << 4) | (b1 >> 4)];
              text[t + 2] =
                i + 1 < bytes ? digits[((b1 & 15) << 2) | (b2 >> 6)] : '=';
              text[t + 3] = i + 2 < bytes ? digits[b2 & 63] : '=';
            }
          out.write(text.data(), t);
          data += bytes;
          n -= bytes;
        }
    }



    /**
     * One binary array of a .vtu file as DataOutBase::write_vtu writes it:
     * the values zlib-compressed into one block, after the block header
     * (number of blocks, block size, size of the last block, compressed
     * size; UInt32), header and block base64-encoded separately. Values are
     * compressed as they are added; only the compressed block is held.
     */
    class CompressedArray
    {
    public:
      CompressedArray(const std::size_t n_bytes, const int level)
        : n_bytes(n_bytes)
      {
        AssertThrow(n_bytes <= std::numeric_limits<std::uint32_t>::max(),
                    ExcMessage("Output: a points array of more than 4 GB "
                               "does not fit the .vtu block header."));
        stream.zalloc = Z_NULL;
        stream.zfree  = Z_NULL;
        stream.opaque = Z_NULL;
        AssertThrow(deflateInit(&stream, level) == Z_OK,
                    ExcMessage("Output: zlib failed to start."));
        capacity = deflateBound(&stream, n_bytes);
        // Not value-initialised: only the pages written are touched.
        compressed.reset(new unsigned char[capacity]);
        stream.next_out  = compressed.get();
        stream.avail_out = capacity;
      }

      ~CompressedArray()
      {
        deflateEnd(&stream);
      }

      template <typename T>
      void
      add(const T value)
      {
        if (staged + sizeof(T) > staging.size())
          deflate_staged(Z_NO_FLUSH);
        std::memcpy(staging.data() + staged, &value, sizeof(T));
        staged += sizeof(T);
      }

      /** Finishes the block and writes it. */
      void
      write(std::ostream &out)
      {
        deflate_staged(Z_FINISH);
        AssertThrow(stream.total_in == n_bytes, ExcInternalError());
        AssertThrow(stream.total_out <=
                      std::numeric_limits<std::uint32_t>::max(),
                    ExcMessage("Output: a compressed points array of more "
                               "than 4 GB does not fit the .vtu header."));
        const std::uint32_t header[4] = {1,
                                         static_cast<std::uint32_t>(n_bytes),
                                         static_cast<std::uint32_t>(n_bytes),
                                         static_cast<std::uint32_t>(
                                           stream.total_out)};
        write_base64(out,
                     reinterpret_cast<const unsigned char *>(header),
                     sizeof(header));
        write_base64(out, compressed.get(), stream.total_out);
      }

    private:
      void
      deflate_staged(const int flush)
      {
        stream.next_in  = staging.data();
        stream.avail_in = staged;
        while (true)
          {
            if (stream.avail_out == 0)
              {
                // deflateBound() holds for one call with all the input;
                // grow if feeding it in pieces ever needs more.
                const std::size_t used = stream.total_out;
                capacity += capacity / 2 + 64;
                std::unique_ptr<unsigned char[]> larger(
                  new unsigned char[capacity]);
                std::memcpy(larger.get(), compressed.get(), used);
                compressed       = std::move(larger);
                stream.next_out  = compressed.get() + used;
                stream.avail_out = capacity - used;
              }
            const int result = deflate(&stream, flush);
            AssertThrow(result == Z_OK || result == Z_STREAM_END ||
                          result == Z_BUF_ERROR,
                        ExcMessage("Output: zlib failed to compress."));
            if (flush == Z_FINISH ?
                  result == Z_STREAM_END :
                  stream.avail_in == 0 && stream.avail_out > 0)
              break;
          }
        staged = 0;
      }

      const std::size_t                    n_bytes;
      z_stream                             stream;
      std::size_t                          capacity;
      std::unique_ptr<unsigned char[]>     compressed;
      std::array<unsigned char, 64 * 1024> staging;
      std::size_t                          staged = 0;
    };



    /** "id" and the property names, as Particles::DataOut names them. */
    std::vector<std::string>
    field_names_of(const MaterialPoints &points)
    {
      std::vector<std::string> names{"id"};
      for (const std::string &name :
           MaterialPoints::property_names(points.n_properties()))
        names.push_back(name);
      return names;
    }
  } // namespace



  PointOutput::PointOutput(const MaterialPoints        &points,
                           const DataOutBase::VtkFlags &flags)
    : particles(points.particle_handler())
    , flags(flags)
    , field_names(field_names_of(points))
    , vectors{{MaterialPoints::Property::displacement + 1,
               MaterialPoints::Property::displacement + 2,
               field_names[MaterialPoints::Property::displacement + 1],
               DataComponentInterpretation::component_is_part_of_vector},
              {MaterialPoints::Property::initial_position + 1,
               MaterialPoints::Property::initial_position + 2,
               field_names[MaterialPoints::Property::initial_position + 1],
               DataComponentInterpretation::component_is_part_of_vector}}
  {}



  template <typename Fill>
  void
  PointOutput::write_point_array(std::ostream      &out,
                                 const unsigned int n_components,
                                 const Fill        &fill) const
  {
    CompressedArray array(particles.n_locally_owned_particles() * n_components *
                            sizeof(float),
                          zlib_level(flags.compression_level));
    std::array<float, 3> values;
    AssertIndexRange(n_components, values.size() + 1);
    for (const auto &particle : particles)
      {
        fill(particle, values.data());
        for (unsigned int c = 0; c < n_components; ++c)
          array.add(values[c]);
      }
    array.write(out);
  }



  void
  PointOutput::write_vtu(std::ostream &out) const
  {
    DataOutBase::write_vtu_header(out, flags);
    const std::size_t n_points = particles.n_locally_owned_particles();
    const int         level    = zlib_level(flags.compression_level);
    std::vector<bool> in_vector(field_names.size(), false);
    for (const Range &range : vectors)
      for (unsigned int f = std::get<0>(range); f <= std::get<1>(range); ++f)
        in_vector[f] = true;

    if (n_points == 0)
      {
        // What DataOutBase writes for a process without points: the
        // smallest piece ParaView and VisIt accept.
        out << "<Piece NumberOfPoints=\"0\" NumberOfCells=\"0\" >\n"
            << "<Cells>\n"
            << "<DataArray type=\"UInt8\" Name=\"types\"></DataArray>\n"
            << "</Cells>\n"
            << "  <PointData Scalars=\"scalars\">\n";
        for (const Range &range : vectors)
          out << "    <DataArray type=\"Float32\" Name=\"" << std::get<2>(range)
              << "\" NumberOfComponents=\"3\"></DataArray>\n";
        for (unsigned int f = 0; f < field_names.size(); ++f)
          if (!in_vector[f])
            out << "    <DataArray type=\"Float32\" Name=\"" << field_names[f]
                << "\"></DataArray>\n";
        out << "  </PointData>\n"
            << "</Piece>\n";
      }
    else
      {
        AssertThrow(n_points <= std::numeric_limits<std::int32_t>::max(),
                    ExcMessage("Output: more points on one process than "
                               "the .vtu file's Int32 cells can number."));
        const char *end_array = "\n    </DataArray>\n";

        out << "<Piece NumberOfPoints=\"" << n_points << "\" NumberOfCells=\""
            << n_points << "\" >\n"
            << "  <Points>\n"
            << "    <DataArray type=\"Float32\" NumberOfComponents=\"3\" "
               "format=\"binary\">\n";
        write_point_array(out, 3, [](const auto &particle, float *values) {
          const Point<2> &x = particle.get_location();
          values[0]         = x[0];
          values[1]         = x[1];
          values[2]         = 0;
        });
        out << end_array << "  </Points>\n\n";

        // One vertex cell per point.
        out << "  <Cells>\n"
            << "    <DataArray type=\"Int32\" Name=\"connectivity\" "
               "format=\"binary\">\n";
        {
          CompressedArray array(n_points * sizeof(std::int32_t), level);
          for (std::size_t i = 0; i < n_points; ++i)
            array.add(static_cast<std::int32_t>(i));
          array.write(out);
        }
        out << end_array
            << "    <DataArray type=\"Int32\" Name=\"offsets\" "
               "format=\"binary\">\n";
        {
          CompressedArray array(n_points * sizeof(std::int32_t), level);
          for (std::size_t i = 0; i < n_points; ++i)
            array.add(static_cast<std::int32_t>(i + 1));
          array.write(out);
        }
        out << end_array
            << "    <DataArray type=\"UInt8\" Name=\"types\" "
               "format=\"binary\">\n";
        {
          constexpr std::uint8_t vtk_vertex = 1;
          CompressedArray        array(n_points, level);
          for (std::size_t i = 0; i < n_points; ++i)
            array.add(vtk_vertex);
          array.write(out);
        }
        out << end_array << "  </Cells>\n";

        // Field 0 is the id, field f > 0 property f - 1.
        const auto field = [](const auto &particle, const unsigned int f) {
          return f == 0 ? static_cast<float>(particle.get_id()) :
                          static_cast<float>(particle.get_properties()[f - 1]);
        };
        out << "  <PointData Scalars=\"scalars\">\n";
        for (const Range &range : vectors)
          {
            out << "    <DataArray type=\"Float32\" Name=\""
                << std::get<2>(range)
                << "\" NumberOfComponents=\"3\" format=\"binary\">\n";
            const unsigned int first = std::get<0>(range);
            const unsigned int last  = std::get<1>(range);
            write_point_array(out, 3, [&](const auto &particle, float *values) {
              for (unsigned int c = 0; c < 3; ++c)
                values[c] = first + c <= last ? field(particle, first + c) : 0;
            });
            out << end_array;
          }
        for (unsigned int f = 0; f < field_names.size(); ++f)
          if (!in_vector[f])
            {
              out << "    <DataArray type=\"Float32\" Name=\"" << field_names[f]
                  << "\" format=\"binary\">\n";
              write_point_array(out,
                                1,
                                [&](const auto &particle, float *values) {
                                  values[0] = field(particle, f);
                                });
              out << end_array;
            }
        out << "  </PointData>\n"
            << " </Piece>\n";
      }
    DataOutBase::write_vtu_footer(out);
    out.flush();
    AssertThrow(out, ExcIO());
  }



  void
  PointOutput::write_pvtu_record(std::ostream                   &out,
                                 const std::vector<std::string> &pieces) const
  {
    DataOutBase::write_pvtu_record(out, pieces, field_names, vectors, flags);
  }
} // namespace bsmpm
