// The studio's bake settings panel: the final gather's settings (rays per
// vertex, near-source distance, near sources' least rays) have controls built
// from their rows of the settings table, start at the bake's defaults, reach
// the BakeSettings a bake gets, survive a save and load, and are disabled when
// they cannot apply.
#include <QDoubleSpinBox>
#include <QSettings>
#include <QSpinBox>

#include "render_support.h"
#include "settings/settings_table.h"
#include "settings_panel.h"

namespace bounce::render_test {

namespace {

// The spin box whose tool tip is the row's studio help.
template <typename Box>
Box* control_of(const studio::SettingsPanel& panel, const char* setting) {
  const QString help = QString::fromUtf8(setting_row(setting).studio_help);
  for (Box* box : panel.findChildren<Box*>())
    if (box->toolTip() == help) return box;
  return nullptr;
}

}  // namespace

TEST(SettingsPanel, FinalGatherSettingsStartAtTheBakesDefaults) {
  const studio::SettingsPanel panel;
  const BakeSettings defaults;
  const BakeSettings s = panel.settings();
  EXPECT_EQ(s.final_gather_rays, defaults.final_gather_rays);
  EXPECT_EQ(s.final_gather_near, defaults.final_gather_near);
  EXPECT_EQ(s.final_gather_near_min_rays, defaults.final_gather_near_min_rays);
  EXPECT_EQ(s.final_gather_spots, defaults.final_gather_spots);
  // Each has its own control, with the row's range.
  QSpinBox* spots = control_of<QSpinBox>(panel, "final_gather_spots");
  ASSERT_NE(spots, nullptr);
  EXPECT_EQ(spots->minimum(), 0);
  EXPECT_EQ(spots->maximum(), static_cast<int>(setting_row("final_gather_spots").max));
  QSpinBox* rays = control_of<QSpinBox>(panel, "final_gather_rays");
  QSpinBox* least = control_of<QSpinBox>(panel, "final_gather_near_min_rays");
  QDoubleSpinBox* near = control_of<QDoubleSpinBox>(panel, "final_gather_near");
  ASSERT_NE(rays, nullptr);
  ASSERT_NE(least, nullptr);
  ASSERT_NE(near, nullptr);
  EXPECT_EQ(rays->minimum(), 0);
  EXPECT_EQ(least->minimum(), 1);
  EXPECT_DOUBLE_EQ(near->maximum(), setting_row("final_gather_near").max);
}

TEST(SettingsPanel, FinalGatherSettingsReachTheBakeAndSurviveSaveAndLoad) {
  studio::SettingsPanel panel;
  panel.set("final_gather_rays", "512");
  panel.set("final_gather_near", "0.125");
  panel.set("final_gather_near_min_rays", "3");
  panel.set("final_gather_spots", "1");
  const BakeSettings s = panel.settings();
  EXPECT_EQ(s.final_gather_spots, 1);
  EXPECT_EQ(s.final_gather_rays, 512);
  EXPECT_DOUBLE_EQ(s.final_gather_near, 0.125);
  EXPECT_EQ(s.final_gather_near_min_rays, 3);
  EXPECT_NO_THROW(s.validate());

  const std::string file = (work_dir("settings-panel") / "studio.ini").string();
  {
    QSettings store(QString::fromStdString(file), QSettings::IniFormat);
    panel.save(store);
  }
  studio::SettingsPanel loaded;
  QSettings store(QString::fromStdString(file), QSettings::IniFormat);
  loaded.load(store);
  const BakeSettings l = loaded.settings();
  EXPECT_EQ(l.final_gather_rays, 512);
  EXPECT_DOUBLE_EQ(l.final_gather_near, 0.125);
  EXPECT_EQ(l.final_gather_near_min_rays, 3);
  EXPECT_EQ(l.final_gather_spots, 1);
}

TEST(SettingsPanel, NearSourceControlsNeedAFinalGather) {
  studio::SettingsPanel panel;
  QDoubleSpinBox* near = control_of<QDoubleSpinBox>(panel, "final_gather_near");
  QSpinBox* least = control_of<QSpinBox>(panel, "final_gather_near_min_rays");
  ASSERT_NE(near, nullptr);
  ASSERT_NE(least, nullptr);
  EXPECT_TRUE(near->isEnabled());
  EXPECT_TRUE(least->isEnabled());
  panel.set("final_gather_near", "0");
  EXPECT_TRUE(near->isEnabled());
  EXPECT_FALSE(least->isEnabled());
  panel.set("final_gather_near", "0.25");
  panel.set("final_gather_rays", "0");
  EXPECT_FALSE(near->isEnabled());
  EXPECT_FALSE(least->isEnabled());
  EXPECT_EQ(panel.settings().final_gather_rays, 0);
  EXPECT_NO_THROW(panel.settings().validate());
}

}  // namespace bounce::render_test
