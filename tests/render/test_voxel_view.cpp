#include "render_support.h"
#include "voxel_view.h"

namespace bounce::render_test {

constexpr std::array<int, 3> kVoxel = {views::VoxelView::kVoxelColour[0],
                                       views::VoxelView::kVoxelColour[1],
                                       views::VoxelView::kVoxelColour[2]};

// The fixture is named like the view, as the CTest list in CMakeLists.txt spells it.
class VoxelView : public RenderTest {
 protected:
  void SetUp() override {
    RenderTest::SetUp();
    data_ = load_fixture();
    view_.resize(640, 480);
    view_.show();
    settle();
    view_.set_data(data_);
    settle();
  }
  std::shared_ptr<const views::BakeViewData> data_;
  views::VoxelView view_;
};

TEST_F(VoxelView, ShowsOccupiedVoxelsInTheirColour) {
  const QImage image = view_.render_image();
  ASSERT_FALSE(image.isNull());
  EXPECT_GT(non_uniform_share(image), 0.2) << "the picture is (nearly) one colour";
  // Every occupied voxel of the bake is shown with no filter...
  EXPECT_EQ(view_.shown_voxels(),
            fixture_manifest()["counts"]["occupied_voxels"].get<std::size_t>());
  // ...as unlit lines of the voxel colour: a wireframe cube edge is at least
  // a few pixels long, so there are many such pixels.
  EXPECT_GT(count_colour(image, kVoxel), 10 * view_.shown_voxels() / 4);
}

TEST_F(VoxelView, FilterAndSliceHideVoxels) {
  const std::size_t before = count_colour(view_.render_image(), kVoxel);
  ASSERT_GT(before, 0u);
  // No voxel holds more samples than the whole bake has.
  view_.set_filter(views::VoxelView::FilterBy::Samples,
                   static_cast<int>(data_->bake.samples.samples.size()) + 1);
  EXPECT_EQ(view_.shown_voxels(), 0u);
  EXPECT_EQ(count_colour(view_.render_image(), kVoxel), 0u);
  // Filter by patches: exactly the voxels with >= 2 patches (counted from voxels.npy).
  std::size_t with_two = 0;
  for (const views::VoxelRow& v : data_->voxels) with_two += v.patches >= 2 ? 1 : 0;
  view_.set_filter(views::VoxelView::FilterBy::Patches, 2);
  EXPECT_EQ(view_.shown_voxels(), with_two);
  view_.set_filter(views::VoxelView::FilterBy::Samples, 0);
  // A horizontal cut halfway up the grid keeps the voxels below it. The
  // Cornell box camera looks horizontally from a height at or above that cut
  // (checked here), so whatever is kept projects onto the lower half of the
  // picture: the upper half must lose every voxel pixel it had.
  const nlohmann::json& grid = data_->bake.manifest["grid"];
  const double cut = grid["origin"][1].get<double>() +
                     0.5 * grid["dims"][1].get<double>() * grid["cell_size"].get<double>();
  ASSERT_TRUE(data_->scene);
  ASSERT_GE(data_->scene->camera.position.y, cut);
  ASSERT_EQ(data_->scene->camera.target.y, data_->scene->camera.position.y);
  auto upper_half = [](const QImage& image) {
    return image.copy(0, 0, image.width(), image.height() / 2 - 2);
  };
  const QImage full = view_.render_image();
  ASSERT_GT(count_colour(upper_half(full), kVoxel), 0u);
  view_.set_slice(true, views::VoxelView::Axis::Y, 0.5);
  const QImage sliced = view_.render_image();
  EXPECT_EQ(count_colour(upper_half(sliced), kVoxel), 0u);
  EXPECT_GT(count_colour(sliced, kVoxel), 0u);
}

}  // namespace bounce::render_test
